//! A proptest-driven fuzzer of the scene parser and validator (no nightly toolchain is assumed on
//! CI, so not cargo-fuzz): arbitrary bytes, and arbitrary TOML trees built from the scene
//! vocabulary with hostile values (NaN, infinities, negative and huge numbers, wrong types,
//! nested tables, unknown keys). Every input must give a scene or one error that names the file;
//! never a panic. Scenes that validate are run when their model is cheap (disk-friction,
//! balls-wall, rigid-impact), which must again end in a result or an error. The case counts bound
//! the time (a few seconds in release); a failure is kept by proptest in
//! `tests/fuzz_scene.proptest-regressions` and replayed first on every later run.

use impactcheck::scene::{Scene, parse, parse_table};
use proptest::prelude::*;

const KEYS: &[&str] = &[
    "model",
    "effects",
    "variant",
    "viscoelastic_law",
    "impactor",
    "material",
    "plate",
    "foundation",
    "inplane",
    "solve",
    "contact",
    "body",
    "initial",
    "support",
    "fixed",
    "mass",
    "v0",
    "theta_deg",
    "E",
    "nu",
    "eta",
    "a",
    "b",
    "h",
    "rho",
    "modes",
    "kw",
    "kg",
    "ct",
    "p1",
    "p2",
    "rtol",
    "atol",
    "method",
    "t_end",
    "samples",
    "k",
    "damping",
    "inertia",
    "contact_offset",
    "normal",
    "mu",
    "law",
    "e",
    "v_rel",
    "offset",
    "axis",
    "sigma",
    "length",
    "stiffness_o",
    "radius",
    "contact_law",
    "wall_stiffness_ratio",
    "stiffness",
    "v",
    "omega",
    "c",
    "zz_top",
];
/// Model and effect names from the scene module, plus the other words scenes use and junk.
fn words() -> Vec<String> {
    impactcheck::scene::REGISTRY
        .iter()
        .map(|(name, _)| *name)
        .chain(impactcheck::scene::EFFECTS.iter().copied())
        .chain([
            "as-printed",
            "corrected",
            "constant-bulk",
            "constant-poisson",
            "poisson",
            "newton",
            "energetic",
            "auto",
            "dop853",
            "radau5",
            "contact-end",
            "inf",
            "linear",
            "",
            "\u{0}",
            "é",
        ])
        .map(String::from)
        .collect()
}

fn number() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(f64::NAN),
        Just(f64::INFINITY),
        Just(f64::NEG_INFINITY),
        Just(0.0),
        Just(-0.0),
        Just(1e308),
        Just(-1e308),
        Just(5e-324),
        -10.0f64..10.0,
        (-300.0f64..300.0).prop_map(|e| 10f64.powf(e)),
    ]
}

fn leaf() -> impl Strategy<Value = toml::Value> {
    prop_oneof![
        number().prop_map(toml::Value::Float),
        any::<i64>().prop_map(toml::Value::Integer),
        any::<bool>().prop_map(toml::Value::Boolean),
        proptest::sample::select(words()).prop_map(toml::Value::String),
        proptest::collection::vec(number(), 0..4)
            .prop_map(|v| toml::Value::Array(v.into_iter().map(toml::Value::Float).collect())),
        proptest::collection::vec(proptest::collection::vec(number(), 0..4), 0..4).prop_map(|v| {
            toml::Value::Array(
                v.into_iter()
                    .map(|r| toml::Value::Array(r.into_iter().map(toml::Value::Float).collect()))
                    .collect(),
            )
        }),
    ]
}

fn value() -> impl Strategy<Value = toml::Value> {
    leaf().prop_recursive(3, 48, 8, |inner| {
        prop_oneof![
            proptest::collection::vec((proptest::sample::select(KEYS), inner.clone()), 0..8)
                .prop_map(|kv| {
                    toml::Value::Table(kv.into_iter().map(|(k, v)| (k.to_string(), v)).collect())
                }),
            proptest::collection::vec(inner, 0..3).prop_map(toml::Value::Array),
        ]
    })
}

fn tree() -> impl Strategy<Value = toml::Table> {
    (
        proptest::sample::select(
            impactcheck::scene::REGISTRY
                .iter()
                .map(|(name, _)| name.to_string())
                .collect::<Vec<_>>(),
        ),
        proptest::collection::vec((proptest::sample::select(KEYS), value()), 0..10),
    )
        .prop_map(|(model, kv)| {
            let mut t: toml::Table = kv.into_iter().map(|(k, v)| (k.to_string(), v)).collect();
            t.entry("model".to_string())
                .or_insert_with(|| toml::Value::String(model));
            t
        })
}

fn cheap(s: &Scene) -> bool {
    matches!(s.model(), "disk-friction" | "balls-wall" | "rigid-impact")
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 3000, ..ProptestConfig::default() })]

    #[test]
    fn arbitrary_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..400)) {
        let text = String::from_utf8_lossy(&bytes);
        if let Err(e) = parse(&text, "fuzz.toml") {
            prop_assert!(e.to_string().starts_with("fuzz.toml"), "{e}");
        }
    }

    /// Near-valid text: a real scene with one line cut, duplicated or garbled.
    #[test]
    fn mangled_scenes_never_panic(
        which in 0usize..9,
        cut in 0usize..2000,
        junk in "[=\\[\\]\"a-z0-9.,# -]{0,12}",
    ) {
        let files = [
            "scenes/hertz.toml", "scenes/cone_plate.toml", "scenes/cone_halfspace_kv.toml",
            "scenes/rigid_impact.toml", "scenes/pendulum_wall.toml", "scenes/billiard_table.toml",
            "scenes/pendulum_on_wall.toml", "scenes/balls_wall.toml", "scenes/disk_friction.toml",
        ];
        let text = std::fs::read_to_string(files[which]).expect("scene");
        let at = text.char_indices().map(|(i, _)| i).nth(cut % text.chars().count().max(1)).unwrap_or(0);
        let mangled = format!("{}{junk}{}", &text[..at], &text[at..]);
        match parse(&mangled, "fuzz.toml") {
            Err(e) => prop_assert!(e.to_string().starts_with("fuzz.toml"), "{e}"),
            Ok(s) if cheap(&s) => { let _ = impactcheck::cli::run_validated(&s); }
            Ok(_) => {}
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, ..ProptestConfig::default() })]

    #[test]
    fn arbitrary_trees_never_panic(t in tree()) {
        match parse_table(&t, "fuzz.toml") {
            Err(e) => prop_assert!(e.to_string().starts_with("fuzz.toml"), "{e}"),
            Ok(s) if cheap(&s) => { let _ = impactcheck::cli::run_validated(&s); }
            Ok(_) => {}
        }
    }
}

/// Every leaf of a table (dotted paths into tables and arrays-of-tables).
fn leaves(t: &toml::Table, prefix: &mut Vec<String>, out: &mut Vec<Vec<String>>) {
    for (k, v) in t {
        prefix.push(k.clone());
        match v {
            toml::Value::Table(inner) => leaves(inner, prefix, out),
            toml::Value::Array(a) if a.iter().all(|x| x.is_table()) && !a.is_empty() => {
                for (i, x) in a.iter().enumerate() {
                    prefix.push(i.to_string());
                    if let toml::Value::Table(inner) = x {
                        leaves(inner, prefix, out);
                    }
                    prefix.pop();
                }
            }
            _ => out.push(prefix.clone()),
        }
        prefix.pop();
    }
}

fn slot<'a>(t: &'a mut toml::Table, path: &[String]) -> Option<&'a mut toml::Value> {
    let (first, rest) = path.split_first()?;
    let mut v = t.get_mut(first)?;
    for p in rest {
        v = match v {
            toml::Value::Table(inner) => inner.get_mut(p)?,
            toml::Value::Array(a) => a.get_mut(p.parse::<usize>().ok()?)?,
            _ => return None,
        };
    }
    Some(v)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 3000, ..ProptestConfig::default() })]

    /// A valid scene with one or two leaves replaced by hostile values: this reaches the
    /// validation of every field (and runs the cheap models on what still validates).
    #[test]
    fn mutated_valid_scenes_never_panic(
        which in 0usize..9,
        picks in proptest::collection::vec((any::<proptest::sample::Index>(), leaf()), 1..3),
    ) {
        let files = [
            "scenes/hertz.toml", "scenes/cone_plate.toml", "scenes/cone_halfspace_kv.toml",
            "scenes/rigid_impact.toml", "scenes/pendulum_wall.toml", "scenes/billiard_table.toml",
            "scenes/pendulum_on_wall.toml", "scenes/balls_wall.toml", "scenes/disk_friction.toml",
        ];
        let mut t = impactcheck::scene::read_table(std::path::Path::new(files[which])).expect("scene");
        let mut all = Vec::new();
        leaves(&t, &mut Vec::new(), &mut all);
        for (ix, v) in picks {
            let path = ix.get(&all).clone();
            if let Some(s) = slot(&mut t, &path) {
                *s = v;
            }
        }
        match parse_table(&t, "fuzz.toml") {
            Err(e) => prop_assert!(e.to_string().starts_with("fuzz.toml"), "{e}"),
            Ok(s) if cheap(&s) => { let _ = impactcheck::cli::run_validated(&s); }
            Ok(_) => {}
        }
    }
}
