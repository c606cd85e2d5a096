//! The values of a swept grid are the ones asked for: `0:1:11` gives 0.3, not
//! 0.30000000000000004 (issue 54), and the ends are the given numbers exactly. The expected
//! values are the decimals typed by hand.

use impactcheck::scene::sweep::parse_vary;

#[test]
fn a_linear_grid_holds_the_decimals_asked_for() {
    let s = parse_vary("impactor.v0=0:1:11", false).expect("parses");
    let want = [0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0];
    assert_eq!(s.values, want);
    // the CSV writes the shortest text of each: 0.3, never 0.30000000000000004
    assert!(
        s.values.iter().all(|v| format!("{v}").len() <= 3),
        "{:?}",
        s.values
    );
    let s = parse_vary("material.E=1e9:2e9:6", false).expect("parses");
    assert_eq!(s.values, [1e9, 1.2e9, 1.4e9, 1.6e9, 1.8e9, 2e9]);
    let s = parse_vary("x=-0.3:0.3:7", false).expect("parses");
    assert_eq!(s.values, [-0.3, -0.2, -0.1, 0.0, 0.1, 0.2, 0.3]);
}

#[test]
fn a_log_grid_holds_the_decades_and_twelve_digits_between() {
    let s = parse_vary("k=1e-4:1e-2:3", true).expect("parses");
    assert_eq!(s.values, [1e-4, 1e-3, 1e-2]);
    // 10^(1/2) between 1 and 10, to 12 significant digits (3.16227766017)
    let s = parse_vary("k=1:10:3", true).expect("parses");
    assert_eq!(s.values[1], 3.16227766017);
    assert!((s.values[1] - 10f64.sqrt()).abs() < 1e-11);
    // a value far below 1e-290 is kept as computed
    let s = parse_vary("k=1e-300:1e-299:3", false).expect("parses");
    assert!(
        s.values[1] > 1e-300 && s.values[1] < 1e-299,
        "{:?}",
        s.values
    );
}
