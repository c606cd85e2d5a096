//! The CSV cells of a run, written straight from its outcome: each number or boolean under the
//! column its dotted path names, and the run's warnings, with no tree built between ([`Node`]
//! sorts every object's keys and allocates every leaf: a fifth of a Hertz sweep's time).
//!
//! The path of a leaf is the one [`Node`]'s flattening gives (an object's key, a sequence's
//! index, an enum variant's name, joined by `.`), and a leaf goes to the column of that path
//! whatever the order the outcome serializes its fields in; of two leaves with one path the
//! last is kept, as [`Node`] keeps the last of equal keys. So the cells are those of the
//! outcome's [`Node`] (tests below, on the outcomes of every shape serde makes).
//!
//! A serde serializer is written here because the cells are a projection that no format crate
//! makes: the walk only keeps the leaves a column names.

use super::row::{Node, NodeError, key_text};
use serde::{Serialize, ser};

/// A number or a boolean of an outcome: what a CSV cell holds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Leaf {
    /// A boolean.
    Bool(bool),
    /// A non-negative integer.
    U64(u64),
    /// A negative integer.
    I64(i64),
    /// A finite float.
    F64(f64),
}

impl Leaf {
    /// The cell's text as [`Node::cell`] writes it (`serde_json`'s format of the number).
    pub fn write(self, out: &mut Vec<u8>) {
        // serde_json's formatter straight (writing to a `Vec` cannot fail), no node made and
        // dropped per cell
        let _ = match self {
            Leaf::Bool(b) => serde_json::to_writer(out, &b),
            Leaf::U64(x) => serde_json::to_writer(out, &x),
            Leaf::I64(x) => serde_json::to_writer(out, &x),
            Leaf::F64(x) => serde_json::to_writer(out, &x),
        };
    }

    /// The leaf of a node that is one.
    pub fn of(node: &Node) -> Option<Leaf> {
        Some(match node {
            Node::Bool(b) => Leaf::Bool(*b),
            Node::U64(x) => Leaf::U64(*x),
            Node::I64(x) => Leaf::I64(*x),
            Node::F64(x) => Leaf::F64(*x),
            _ => return None,
        })
    }
}

/// The cells of one run: the leaf under each column (`None`: the run has none there), the
/// strings of its top-level `warnings`, and for each leaf met, in the order met, the column it
/// went to (`usize::MAX`: none), which the next run of the same model is given as its `plan`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Cells {
    /// One per column.
    pub leaves: Vec<Option<Leaf>>,
    /// The `warnings` strings, in order.
    pub warnings: Vec<String>,
    /// The column of each leaf met.
    pub order: Vec<usize>,
}

/// The cells of `v` under `cols`. `plan` is the `order` of an earlier run of the same model:
/// a leaf whose path is the column the plan names costs one comparison; any other is looked for
/// among all the columns (so a plan that does not fit changes the time, never the cells).
pub fn of<T: Serialize + ?Sized>(
    v: &T,
    cols: &[String],
    plan: &[usize],
) -> Result<Cells, NodeError> {
    let mut w = Walk {
        cols,
        plan,
        path: String::with_capacity(64),
        cells: Cells {
            leaves: vec![None; cols.len()],
            warnings: Vec::new(),
            order: Vec::with_capacity(plan.len()),
        },
    };
    v.serialize(&mut w)?;
    Ok(w.cells)
}

struct Walk<'c> {
    cols: &'c [String],
    plan: &'c [usize],
    path: String,
    cells: Cells,
}

impl Walk<'_> {
    fn leaf(&mut self, leaf: Leaf) {
        let k = self.cells.order.len();
        let planned = self
            .plan
            .get(k)
            .copied()
            .filter(|&i| self.cols.get(i).is_some_and(|c| *c == self.path));
        let at = planned.or_else(|| self.cols.iter().position(|c| *c == self.path));
        if let Some(i) = at {
            self.cells.leaves[i] = Some(leaf);
        }
        self.cells.order.push(at.unwrap_or(usize::MAX));
    }

    /// A string: kept when it is an entry of the top-level `warnings`.
    fn text(&mut self, s: &str) {
        let entry = self.path.strip_prefix("warnings.");
        if entry.is_some_and(|i| !i.is_empty() && i.bytes().all(|b| b.is_ascii_digit())) {
            self.cells.warnings.push(s.to_string());
        }
    }

    /// Appends one segment to the path; returns the length to truncate back to.
    fn enter(&mut self, segment: &str) -> usize {
        let len = self.path.len();
        if len > 0 {
            self.path.push('.');
        }
        self.path.push_str(segment);
        len
    }

    fn enter_index(&mut self, i: usize) -> usize {
        use std::fmt::Write as _;
        let len = self.path.len();
        let _ = write!(self.path, ".{i}");
        len
    }
}

/// A sequence or an object being walked: the walk, the next index of a sequence, the key of a
/// map entry waiting for its value, and the length to truncate the path back to at its end
/// (the variant it is under, if any).
struct Inner<'w, 'c> {
    w: &'w mut Walk<'c>,
    next: usize,
    key: Option<usize>,
    back: Option<usize>,
}

impl Inner<'_, '_> {
    fn element<T: Serialize + ?Sized>(&mut self, v: &T) -> Result<(), NodeError> {
        let len = self.w.enter_index(self.next);
        self.next += 1;
        v.serialize(&mut *self.w)?;
        self.w.path.truncate(len);
        Ok(())
    }

    fn field<T: Serialize + ?Sized>(&mut self, key: &str, v: &T) -> Result<(), NodeError> {
        let len = self.w.enter(key);
        v.serialize(&mut *self.w)?;
        self.w.path.truncate(len);
        Ok(())
    }

    fn done(self) -> Result<(), NodeError> {
        if let Some(len) = self.back {
            self.w.path.truncate(len);
        }
        Ok(())
    }
}

impl<'w, 'c> ser::Serializer for &'w mut Walk<'c> {
    type Ok = ();
    type Error = NodeError;
    type SerializeSeq = Inner<'w, 'c>;
    type SerializeTuple = Inner<'w, 'c>;
    type SerializeTupleStruct = Inner<'w, 'c>;
    type SerializeTupleVariant = Inner<'w, 'c>;
    type SerializeMap = Inner<'w, 'c>;
    type SerializeStruct = Inner<'w, 'c>;
    type SerializeStructVariant = Inner<'w, 'c>;

    fn serialize_bool(self, v: bool) -> Result<(), NodeError> {
        self.leaf(Leaf::Bool(v));
        Ok(())
    }
    fn serialize_i8(self, v: i8) -> Result<(), NodeError> {
        self.serialize_i64(v.into())
    }
    fn serialize_i16(self, v: i16) -> Result<(), NodeError> {
        self.serialize_i64(v.into())
    }
    fn serialize_i32(self, v: i32) -> Result<(), NodeError> {
        self.serialize_i64(v.into())
    }
    fn serialize_i64(self, v: i64) -> Result<(), NodeError> {
        self.leaf(match u64::try_from(v) {
            Ok(u) => Leaf::U64(u),
            Err(_) => Leaf::I64(v),
        });
        Ok(())
    }
    fn serialize_u8(self, v: u8) -> Result<(), NodeError> {
        self.serialize_u64(v.into())
    }
    fn serialize_u16(self, v: u16) -> Result<(), NodeError> {
        self.serialize_u64(v.into())
    }
    fn serialize_u32(self, v: u32) -> Result<(), NodeError> {
        self.serialize_u64(v.into())
    }
    fn serialize_u64(self, v: u64) -> Result<(), NodeError> {
        self.leaf(Leaf::U64(v));
        Ok(())
    }
    fn serialize_f32(self, v: f32) -> Result<(), NodeError> {
        self.serialize_f64(v.into())
    }
    fn serialize_f64(self, v: f64) -> Result<(), NodeError> {
        // a non-finite float is `null` in the outcome's JSON: no cell
        if v.is_finite() {
            self.leaf(Leaf::F64(v));
        }
        Ok(())
    }
    fn serialize_char(self, v: char) -> Result<(), NodeError> {
        self.text(&v.to_string());
        Ok(())
    }
    fn serialize_str(self, v: &str) -> Result<(), NodeError> {
        self.text(v);
        Ok(())
    }
    fn serialize_bytes(self, v: &[u8]) -> Result<(), NodeError> {
        use ser::SerializeSeq;
        let mut s = self.serialize_seq(Some(v.len()))?;
        for b in v {
            s.serialize_element(b)?;
        }
        s.end()
    }
    fn serialize_none(self) -> Result<(), NodeError> {
        Ok(())
    }
    fn serialize_some<T: Serialize + ?Sized>(self, v: &T) -> Result<(), NodeError> {
        v.serialize(self)
    }
    fn serialize_unit(self) -> Result<(), NodeError> {
        Ok(())
    }
    fn serialize_unit_struct(self, _name: &'static str) -> Result<(), NodeError> {
        Ok(())
    }
    fn serialize_unit_variant(
        self,
        _name: &'static str,
        _index: u32,
        variant: &'static str,
    ) -> Result<(), NodeError> {
        self.text(variant);
        Ok(())
    }
    fn serialize_newtype_struct<T: Serialize + ?Sized>(
        self,
        _name: &'static str,
        v: &T,
    ) -> Result<(), NodeError> {
        v.serialize(self)
    }
    fn serialize_newtype_variant<T: Serialize + ?Sized>(
        self,
        _name: &'static str,
        _index: u32,
        variant: &'static str,
        v: &T,
    ) -> Result<(), NodeError> {
        let len = self.enter(variant);
        v.serialize(&mut *self)?;
        self.path.truncate(len);
        Ok(())
    }
    fn serialize_seq(self, _len: Option<usize>) -> Result<Inner<'w, 'c>, NodeError> {
        Ok(Inner {
            w: self,
            next: 0,
            key: None,
            back: None,
        })
    }
    fn serialize_tuple(self, len: usize) -> Result<Inner<'w, 'c>, NodeError> {
        self.serialize_seq(Some(len))
    }
    fn serialize_tuple_struct(
        self,
        _name: &'static str,
        len: usize,
    ) -> Result<Inner<'w, 'c>, NodeError> {
        self.serialize_seq(Some(len))
    }
    fn serialize_tuple_variant(
        self,
        _name: &'static str,
        _index: u32,
        variant: &'static str,
        _len: usize,
    ) -> Result<Inner<'w, 'c>, NodeError> {
        let back = Some(self.enter(variant));
        Ok(Inner {
            w: self,
            next: 0,
            key: None,
            back,
        })
    }
    fn serialize_map(self, _len: Option<usize>) -> Result<Inner<'w, 'c>, NodeError> {
        self.serialize_seq(None)
    }
    fn serialize_struct(
        self,
        _name: &'static str,
        _len: usize,
    ) -> Result<Inner<'w, 'c>, NodeError> {
        self.serialize_seq(None)
    }
    fn serialize_struct_variant(
        self,
        name: &'static str,
        index: u32,
        variant: &'static str,
        len: usize,
    ) -> Result<Inner<'w, 'c>, NodeError> {
        self.serialize_tuple_variant(name, index, variant, len)
    }
}

super::row::seq_shapes!(Inner<'_, '_>, ());
super::row::struct_shapes!(Inner<'_, '_>, ());

impl ser::SerializeMap for Inner<'_, '_> {
    type Ok = ();
    type Error = NodeError;
    /// The key appended to the path: a string written there straight (no node, no string made
    /// per key: the text model's outcome has a dozen), any other through its [`Node`].
    fn serialize_key<T: Serialize + ?Sized>(&mut self, k: &T) -> Result<(), NodeError> {
        let len = self.w.path.len();
        if len > 0 {
            self.w.path.push('.');
        }
        if k.serialize(KeyStr(&mut self.w.path)).is_err() {
            self.w.path.truncate(len);
            let text = key_text(Node::of(k)?)?;
            self.w.enter(&text);
        }
        self.key = Some(len);
        Ok(())
    }
    fn serialize_value<T: Serialize + ?Sized>(&mut self, v: &T) -> Result<(), NodeError> {
        let len = self
            .key
            .take()
            .ok_or_else(|| NodeError("a map value without its key".into()))?;
        v.serialize(&mut *self.w)?;
        self.w.path.truncate(len);
        Ok(())
    }
    fn end(self) -> Result<(), NodeError> {
        self.done()
    }
}

/// Writes a string key (or a newtype of one) at the end of a path; refuses every other value,
/// untouched, so that the caller takes the general way ([`key_text`]).
struct KeyStr<'p>(&'p mut String);

/// The refusal: not a string.
fn not_str<T>() -> Result<T, NodeError> {
    Err(NodeError(String::new()))
}

macro_rules! refuse {
    ($($method:ident($($arg:ty),*)),* $(,)?) => {
        $(fn $method(self $(, _: $arg)*) -> Result<(), NodeError> {
            not_str()
        })*
    };
}

impl ser::Serializer for KeyStr<'_> {
    type Ok = ();
    type Error = NodeError;
    type SerializeSeq = ser::Impossible<(), NodeError>;
    type SerializeTuple = ser::Impossible<(), NodeError>;
    type SerializeTupleStruct = ser::Impossible<(), NodeError>;
    type SerializeTupleVariant = ser::Impossible<(), NodeError>;
    type SerializeMap = ser::Impossible<(), NodeError>;
    type SerializeStruct = ser::Impossible<(), NodeError>;
    type SerializeStructVariant = ser::Impossible<(), NodeError>;
    fn serialize_str(self, v: &str) -> Result<(), NodeError> {
        self.0.push_str(v);
        Ok(())
    }
    fn serialize_newtype_struct<T: Serialize + ?Sized>(
        self,
        _name: &'static str,
        v: &T,
    ) -> Result<(), NodeError> {
        v.serialize(self)
    }
    refuse!(
        serialize_bool(bool),
        serialize_i8(i8),
        serialize_i16(i16),
        serialize_i32(i32),
        serialize_i64(i64),
        serialize_u8(u8),
        serialize_u16(u16),
        serialize_u32(u32),
        serialize_u64(u64),
        serialize_f32(f32),
        serialize_f64(f64),
        serialize_char(char),
        serialize_bytes(&[u8]),
        serialize_none(),
        serialize_unit(),
        serialize_unit_struct(&'static str),
        serialize_unit_variant(&'static str, u32, &'static str),
    );
    fn serialize_some<T: Serialize + ?Sized>(self, _: &T) -> Result<(), NodeError> {
        not_str()
    }
    fn serialize_newtype_variant<T: Serialize + ?Sized>(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: &T,
    ) -> Result<(), NodeError> {
        not_str()
    }
    fn serialize_seq(self, _: Option<usize>) -> Result<Self::SerializeSeq, NodeError> {
        not_str()
    }
    fn serialize_tuple(self, _: usize) -> Result<Self::SerializeTuple, NodeError> {
        not_str()
    }
    fn serialize_tuple_struct(
        self,
        _: &'static str,
        _: usize,
    ) -> Result<Self::SerializeTupleStruct, NodeError> {
        not_str()
    }
    fn serialize_tuple_variant(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: usize,
    ) -> Result<Self::SerializeTupleVariant, NodeError> {
        not_str()
    }
    fn serialize_map(self, _: Option<usize>) -> Result<Self::SerializeMap, NodeError> {
        not_str()
    }
    fn serialize_struct(
        self,
        _: &'static str,
        _: usize,
    ) -> Result<Self::SerializeStruct, NodeError> {
        not_str()
    }
    fn serialize_struct_variant(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
        _: usize,
    ) -> Result<Self::SerializeStructVariant, NodeError> {
        not_str()
    }
}

#[cfg(test)]
mod tests {
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
                    if let (Some(l), Some(i)) =
                        (Leaf::of(leaf), cols.iter().position(|c| c == path))
                    {
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
        let got = of(out, cols, &[]).expect("walks");
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
        // the plan of the first run takes the second to the same cells, and a plan that does
        // not fit (another model's) changes nothing
        let again = of(&v, &cols, &first.order).expect("walks");
        assert_eq!(again, first);
        let wrong: Vec<usize> = first.order.iter().rev().copied().collect();
        assert_eq!(of(&v, &cols, &wrong).expect("walks").leaves, want);
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
        let got = of(&out, &cols, &[]).expect("walks");
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
        assert!(of(&m, &[], &[]).is_err());
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
}
