//! The cells against the outcome's tree ([`Node`]), on every shape serde makes, and a walk
//! against every trail.

use super::*;
use serde_json::json;

/// The reference: the outcome's [`Node`], each leaf put under its column by the node's own
/// flattening (the path text of `impact sweep`'s columns), the warnings read from its
/// `warnings` field.
fn by_node(v: &serde_json::Value, cols: &[String]) -> (Vec<Option<Leaf>>, Vec<String>) {
    fn walk(n: &Node, path: &str, cols: &[String], out: &mut Vec<Option<Leaf>>) {
        match n {
            Node::Obj(fields) => {
                for (k, x) in fields {
                    let p = if path.is_empty() {
                        k.to_string()
                    } else {
                        format!("{path}.{k}")
                    };
                    walk(x, &p, cols, out);
                }
            }
            Node::Arr(items) => {
                for (i, x) in items.iter().enumerate() {
                    walk(x, &format!("{path}.{i}"), cols, out);
                }
            }
            leaf => {
                if let (Some(l), Some(i)) = (Leaf::of(leaf), cols.iter().position(|c| c == path)) {
                    out[i] = Some(l);
                }
            }
        }
    }
    let node = Node::from_value(v);
    let mut leaves = vec![None; cols.len()];
    walk(&node, "", cols, &mut leaves);
    let warnings = match node.get("warnings") {
        Some(Node::Arr(w)) => w
            .iter()
            .filter_map(|x| match x {
                Node::Str(s) => Some(s.clone()),
                _ => None,
            })
            .collect(),
        _ => Vec::new(),
    };
    (leaves, warnings)
}

/// The cells of `out` (whose JSON is `value`) under `cols`, checked against the tree's
/// ([`by_node`]): leaves and warnings; and the tree's leaves.
fn walked_as_the_tree<T: Serialize>(
    out: &T,
    value: &serde_json::Value,
    cols: &[String],
) -> (Cells, Vec<Option<Leaf>>) {
    let (want, warnings) = by_node(value, cols);
    let got = of(out, cols, &Trail::default()).expect("walks");
    assert_eq!(got.leaves, want);
    assert_eq!(got.warnings, warnings);
    (got, want)
}

#[test]
fn the_cells_are_those_of_the_outcomes_tree() {
    // objects (serialized as maps here, in their keys' order), nested arrays, negative
    // integers, nulls, a boolean, strings, warnings; the columns in another order than the
    // walk's, one column no run has, one leaf no column names
    let v = json!({
        "stats": {"steps": 12, "rejected": 0},
        "contact": {"duration": 1.5e-4, "ended": true, "peak": null},
        "impulse": [1.0, -2, [3.5, 4]],
        "warnings": ["atol tightened", "a, b"],
        "law": "hertz",
        "unnamed": 7
    });
    let cols: Vec<String> = [
        "stats.steps",
        "impulse.2.1",
        "contact.ended",
        "impulse.1",
        "contact.duration",
        "nowhere",
        "impulse.0",
        "stats.rejected",
        "impulse.2.0",
        "contact.peak",
    ]
    .map(String::from)
    .to_vec();
    let (first, want) = walked_as_the_tree(&v, &v, &cols);
    assert_eq!(first.warnings, ["atol tightened", "a, b"]);
    assert_eq!(first.leaves[1], Some(Leaf::U64(4)));
    assert_eq!(first.leaves[3], Some(Leaf::I64(-2)));
    assert_eq!(first.leaves[5], None, "no run has `nowhere`");
    assert_eq!(first.leaves[9], None, "null is no cell");
    // the trail of the first run takes the second to the same cells (and is not recorded
    // again), and a trail that does not fit (another model's) changes nothing
    let again = of(&v, &cols, &first.trail).expect("walks");
    assert_eq!(
        (&again.leaves, &again.warnings),
        (&first.leaves, &first.warnings)
    );
    assert!(again.trail.0.is_empty() && !first.trail.0.is_empty());
    let other = of(&json!({"b": 1, "a": [2]}), &cols, &Trail::default()).expect("walks");
    assert_eq!(of(&v, &cols, &other.trail).expect("walks").leaves, want);
}

#[derive(Serialize)]
enum Shape {
    Unit,
    Pair(f64, f64),
    Wrapped(u8),
    Named { a: i32, b: Option<f64> },
}

#[derive(Serialize)]
struct Outcome {
    model: &'static str,
    warnings: Vec<String>,
    shapes: Vec<Shape>,
    tuple: (u16, bool),
    lost: f64,
    not_finite: f64,
    bytes: Option<()>,
}

#[test]
fn every_shape_serde_makes_lands_where_the_tree_puts_it() {
    let out = Outcome {
        model: "x",
        warnings: vec!["w".into()],
        shapes: vec![
            Shape::Unit,
            Shape::Pair(1.0, -0.5),
            Shape::Wrapped(3),
            Shape::Named { a: -4, b: None },
            Shape::Named { a: 5, b: Some(2.5) },
        ],
        tuple: (9, false),
        lost: -1.25e-3,
        not_finite: f64::NAN,
        bytes: None,
    };
    let value = serde_json::to_value(&out).expect("serializes");
    // every leaf path the tree has is a column
    let mut cols: Vec<String> = Vec::new();
    fn paths(v: &serde_json::Value, path: &str, out: &mut Vec<String>) {
        match v {
            serde_json::Value::Object(m) => {
                for (k, x) in m {
                    let p = if path.is_empty() {
                        k.clone()
                    } else {
                        format!("{path}.{k}")
                    };
                    paths(x, &p, out);
                }
            }
            serde_json::Value::Array(a) => {
                for (i, x) in a.iter().enumerate() {
                    paths(x, &format!("{path}.{i}"), out);
                }
            }
            _ => out.push(path.to_string()),
        }
    }
    paths(&value, "", &mut cols);
    assert!(cols.contains(&"shapes.3.Named.a".to_string()), "{cols:?}");
    let (want, warnings) = by_node(&value, &cols);
    let got = of(&out, &cols, &Trail::default()).expect("walks");
    assert_eq!(got.leaves, want);
    assert_eq!(got.warnings, warnings);
    let at = |c: &str| got.leaves[cols.iter().position(|x| x == c).expect("a column")];
    assert_eq!(at("shapes.1.Pair.1"), Some(Leaf::F64(-0.5)));
    assert_eq!(at("shapes.2.Wrapped"), Some(Leaf::U64(3)));
    assert_eq!(at("shapes.4.Named.b"), Some(Leaf::F64(2.5)));
    assert_eq!(at("tuple.1"), Some(Leaf::Bool(false)));
    assert_eq!(at("not_finite"), None);
    // the cell text is the tree's
    for (leaf, node) in [
        (Leaf::F64(-1.25e-3), Node::F64(-1.25e-3)),
        (Leaf::U64(9), Node::U64(9)),
        (Leaf::I64(-4), Node::I64(-4)),
        (Leaf::Bool(true), Node::Bool(true)),
        (Leaf::Bool(false), Node::Bool(false)),
        (
            Leaf::F64(7.703347838415442e-14),
            Node::F64(7.703347838415442e-14),
        ),
        (Leaf::F64(1070.5636842899323), Node::F64(1070.5636842899323)),
        (Leaf::F64(-0.0), Node::F64(-0.0)),
        (Leaf::U64(u64::MAX), Node::U64(u64::MAX)),
        (Leaf::I64(i64::MIN), Node::I64(i64::MIN)),
    ] {
        let (mut a, mut b) = (Vec::new(), Vec::new());
        leaf.write(&mut a);
        node.cell(&mut b);
        assert_eq!(a, b);
        assert_eq!(Leaf::of(&node), Some(leaf));
    }
    assert_eq!(Leaf::of(&Node::Null), None);
}

#[test]
fn a_map_key_that_is_no_text_is_an_error() {
    let mut m = std::collections::BTreeMap::new();
    m.insert(vec![1u8], 2.0);
    assert!(of(&m, &[], &Trail::default()).is_err());
}

#[derive(Serialize, PartialEq, Eq, PartialOrd, Ord)]
struct Label(&'static str);

/// Maps keyed by every kind a key may be (strings, a newtype of one, integers of either
/// sign, booleans, chars), nested in a struct and in each other: each leaf lands where the
/// tree puts it, the path back where it was after each entry (the next field's column is
/// right), and the walk's path is the tree's text for each key.
#[test]
fn every_kind_of_map_key_lands_where_the_tree_puts_it() {
    use std::collections::BTreeMap;
    #[derive(Serialize)]
    struct Keys {
        named: BTreeMap<&'static str, BTreeMap<Label, f64>>,
        signed: BTreeMap<i32, u64>,
        unsigned: BTreeMap<u8, bool>,
        flags: BTreeMap<bool, i64>,
        letters: BTreeMap<char, f64>,
        after: f64,
    }
    let out = Keys {
        named: BTreeMap::from([
            (
                "contact-end",
                BTreeMap::from([(Label("z"), 1.5), (Label("v"), -2.0)]),
            ),
            ("", BTreeMap::from([(Label("x.y"), 3.0)])),
        ]),
        signed: BTreeMap::from([(-3, 7), (12, 8)]),
        unsigned: BTreeMap::from([(0, true), (255, false)]),
        flags: BTreeMap::from([(false, -1), (true, 1)]),
        letters: BTreeMap::from([('k', 0.25)]),
        after: 9.5,
    };
    let value = serde_json::to_value(&out).expect("serializes");
    let cols: Vec<String> = [
        "named.contact-end.z",
        "named.contact-end.v",
        "named..x.y",
        "signed.-3",
        "signed.12",
        "unsigned.0",
        "unsigned.255",
        "flags.false",
        "flags.true",
        "letters.k",
        "after",
    ]
    .map(String::from)
    .to_vec();
    let (got, want) = walked_as_the_tree(&out, &value, &cols);
    assert!(want.iter().all(Option::is_some), "{want:?}");
    assert_eq!(got.leaves[1], Some(Leaf::F64(-2.0)));
    assert_eq!(got.leaves[3], Some(Leaf::U64(7)));
    assert_eq!(got.leaves[7], Some(Leaf::I64(-1)));
    assert_eq!(got.leaves[10], Some(Leaf::F64(9.5)));
}

thread_local! {
    /// The times a walk left its plan, on this thread.
    pub(super) static LEFT: std::cell::Cell<usize> = const { std::cell::Cell::new(0) };
}

/// Outcomes of one type whose shapes differ (warnings or none, more or fewer elements,
/// another variant, an option absent, a float not finite, a map with other keys), each
/// walked following the trail of each: the cells are the outcome's tree's whatever the
/// trail, the walk stays on a trail of its own shape to the end and leaves one that
/// does not fit.
#[test]
fn a_walk_on_any_trail_gives_the_trees_cells() {
    use std::collections::BTreeMap;
    #[derive(Serialize)]
    struct Inner {
        pair: (f64, f64),
        tail: f64,
    }
    #[derive(Serialize)]
    struct Run {
        model: &'static str,
        shapes: Vec<Shape>,
        warnings: Vec<String>,
        inner: Inner,
        by: BTreeMap<String, f64>,
        b: Option<u8>,
    }
    let run = |w: &[&str], shapes: Vec<Shape>, first: f64, keys: &[&str], b: Option<u8>| Run {
        model: "x",
        shapes,
        warnings: w.iter().map(|s| s.to_string()).collect(),
        inner: Inner {
            pair: (first, 2.0),
            tail: 3.0,
        },
        by: keys.iter().map(|k| (k.to_string(), 0.5)).collect(),
        b,
    };
    let (named, pair, nan) = (|a, b| Shape::Named { a, b }, Shape::Pair, f64::NAN);
    let long = |s: Shape| {
        let mut v: Vec<Shape> = (0..10).map(|_| Shape::Unit).collect();
        v.extend([s, Shape::Wrapped(2)]);
        v
    };
    let runs = [
        run(&[], vec![pair(1.0, 2.0)], -1.0, &["end"], Some(1)),
        run(&[], vec![pair(3.0, 4.0)], -2.0, &["end"], Some(2)),
        run(&["w"], vec![pair(1.0, 2.0)], 0.0, &["end"], None),
        run(&["w", "v"], vec![], nan, &["end", "peak"], Some(3)),
        run(
            &[],
            vec![Shape::Unit, named(-4, None)],
            1.0,
            &["peak"],
            None,
        ),
        run(
            &[],
            vec![named(5, Some(2.5)), Shape::Wrapped(3)],
            1.0,
            &[],
            Some(0),
        ),
        // the shape of the last but with a float that is not finite deep in the first
        // element: the walk leaves the trail there and must come back out to the second
        run(
            &[],
            vec![pair(nan, 2.5), Shape::Wrapped(3)],
            1.0,
            &[],
            Some(0),
        ),
        run(
            &[],
            vec![pair(1.5, 2.5), Shape::Wrapped(4)],
            1.0,
            &[],
            Some(0),
        ),
        // the same at an index of two digits
        run(&[], long(pair(nan, 1.0)), 1.0, &[], None),
        run(&[], long(pair(0.5, 1.0)), 1.0, &[], None),
    ];
    let values: Vec<serde_json::Value> = runs
        .iter()
        .map(|r| serde_json::to_value(r).expect("serializes"))
        .collect();
    let mut cols: Vec<String> = [
        "shapes.0.Pair.0",
        "shapes.0.Pair.1",
        "shapes.0.Named.a",
        "shapes.0.Named.b",
        "shapes.1.Named.a",
        "shapes.1.Wrapped",
        "shapes.10.Pair.1",
        "shapes.11.Wrapped",
        "inner.pair.0",
        "inner.pair.1",
        "inner.tail",
        "by.end",
        "by.peak",
        "b",
    ]
    .map(String::from)
    .to_vec();
    cols.reverse();
    let trails: Vec<Trail> = runs
        .iter()
        .map(|r| of(r, &cols, &Trail::default()).expect("walks").trail)
        .collect();
    for (i, (r, value)) in runs.iter().zip(&values).enumerate() {
        let (want, warnings) = by_node(value, &cols);
        for (j, trail) in trails.iter().enumerate() {
            let left = LEFT.with(std::cell::Cell::get);
            let got = of(r, &cols, trail).expect("walks");
            assert_eq!(
                (&got.leaves, &got.warnings),
                (&want, &warnings),
                "run {i} on {j}"
            );
            // a trail of the same steps is one of the same shape
            let stayed = LEFT.with(std::cell::Cell::get) == left;
            assert_eq!(
                stayed,
                trails[i] == trails[j],
                "run {i} on the trail of {j}"
            );
        }
    }
}
