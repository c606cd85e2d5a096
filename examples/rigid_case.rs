//! Prints one seeded random rigid impact of the sweep benchmark: its inputs (B, V-, mu, e), the
//! stick threshold mu* = |B_tt^-1 B_tn| and the outcome (phases, impulse) or the error.
fn main() {
    let i: u64 = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(0);
    let (b, v, mu, e) = impactcheck::models::samples::rigid_inputs(i);
    println!("case {i}: B = {b:?}\nV- = {v:?}, mu = {mu}, e = {e}");
    let btt = nalgebra::Matrix2::new(b[(0, 0)], b[(0, 1)], b[(1, 0)], b[(1, 1)]);
    let btn = nalgebra::Vector2::new(b[(0, 2)], b[(1, 2)]);
    if let Some(inv) = btt.try_inverse() {
        println!("mu* = {}", (inv * btn).norm());
    }
    match impactcheck::models::samples::rigid_case(i) {
        Ok(r) => println!(
            "impulse {:?}; {} phases: {:?}; stats {}",
            r.impulse,
            r.phases.len(),
            r.phases
                .iter()
                .take(12)
                .map(|p| (p.kind.clone(), p.normal_impulse))
                .collect::<Vec<_>>(),
            r.stats
        ),
        Err(e) => println!("error: {e}"),
    }
}
