//! A run's outcome as a light tree, for the rows of a sweep.
//!
//! `impact sweep` writes one row per point, and at 10^5 points a second the outcome's trip
//! through `serde_json::Value` (a map node and an owned key per field, all freed again) cost
//! a sixth of the time. A [`Node`] keeps what a row needs: object fields in a `Vec` under their
//! static names, numbers as they came. It is written exactly as the `Value` would be: object
//! keys in sorted order (a later duplicate replacing an earlier one, as a map does), a
//! non-finite float as `null`, numbers in `serde_json`'s own format (the test below checks
//! byte equality on every scene in `scenes/`). Written here because `serde_json` has no
//! lighter owned tree and its `Value` is the cost itself.

use serde::ser::{self, Serialize};
use std::borrow::Cow;

/// One value of an outcome.
#[derive(Clone, Debug, PartialEq)]
pub enum Node {
    /// `null` (also a non-finite float, as in `serde_json`).
    Null,
    /// A boolean.
    Bool(bool),
    /// A finite float.
    F64(f64),
    /// A non-negative integer.
    U64(u64),
    /// A negative integer.
    I64(i64),
    /// A string.
    Str(String),
    /// A sequence.
    Arr(Vec<Node>),
    /// An object, its keys sorted and distinct.
    Obj(Vec<(Cow<'static, str>, Node)>),
}

/// What cannot become a [`Node`] (a map key that is not a string or a number, an integer
/// beyond 64 bits, a custom serializer's error).
#[derive(Debug)]
pub struct NodeError(pub(crate) String);

impl std::fmt::Display for NodeError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for NodeError {}

impl ser::Error for NodeError {
    fn custom<T: std::fmt::Display>(msg: T) -> Self {
        NodeError(msg.to_string())
    }
}

impl Node {
    /// The tree of a serializable value.
    pub fn of<T: Serialize + ?Sized>(v: &T) -> Result<Node, NodeError> {
        v.serialize(NodeSer)
    }

    /// The tree of a JSON value (a merged shard's outcome).
    pub fn from_value(v: &serde_json::Value) -> Node {
        use serde_json::Value;
        match v {
            Value::Null => Node::Null,
            Value::Bool(b) => Node::Bool(*b),
            Value::Number(n) => match (n.as_u64(), n.as_i64(), n.as_f64()) {
                (Some(u), _, _) => Node::U64(u),
                (None, Some(i), _) => Node::I64(i),
                (None, None, Some(x)) => Node::F64(x),
                _ => Node::Null,
            },
            Value::String(s) => Node::Str(s.clone()),
            Value::Array(a) => Node::Arr(a.iter().map(Node::from_value).collect()),
            Value::Object(m) => Node::Obj(
                m.iter()
                    .map(|(k, x)| (Cow::Owned(k.clone()), Node::from_value(x)))
                    .collect(),
            ),
        }
    }

    /// Whether this is a number (`Value::is_number`).
    pub fn is_number(&self) -> bool {
        matches!(self, Node::F64(_) | Node::U64(_) | Node::I64(_))
    }

    /// The field `key` of an object.
    pub fn get(&self, key: &str) -> Option<&Node> {
        match self {
            Node::Obj(fields) => fields.iter().find(|(k, _)| k == key).map(|(_, v)| v),
            _ => None,
        }
    }

    /// Writes the compact JSON text `serde_json::to_string` gives for the same `Value`.
    pub fn write_json(&self, out: &mut Vec<u8>) {
        match self {
            Node::Null => out.extend_from_slice(b"null"),
            Node::Bool(b) => out.extend_from_slice(if *b { b"true" } else { b"false" }),
            Node::F64(x) => write_json_value(out, x),
            Node::U64(x) => write_json_value(out, x),
            Node::I64(x) => write_json_value(out, x),
            Node::Str(s) => write_json_value(out, s.as_str()),
            Node::Arr(a) => {
                out.push(b'[');
                for (i, x) in a.iter().enumerate() {
                    if i > 0 {
                        out.push(b',');
                    }
                    x.write_json(out);
                }
                out.push(b']');
            }
            Node::Obj(fields) => {
                out.push(b'{');
                for (i, (k, x)) in fields.iter().enumerate() {
                    if i > 0 {
                        out.push(b',');
                    }
                    write_json_value(out, k.as_ref());
                    out.push(b':');
                    x.write_json(out);
                }
                out.push(b'}');
            }
        }
    }

    /// Writes a number or boolean as a CSV cell: the text `serde_json` displays for it (its
    /// serializer and its `Display` format a number alike); false, writing nothing, for
    /// anything else.
    pub fn cell(&self, out: &mut Vec<u8>) -> bool {
        match self {
            Node::F64(_) | Node::U64(_) | Node::I64(_) | Node::Bool(_) => {
                self.write_json(out);
                true
            }
            _ => false,
        }
    }
}

/// One scalar in `serde_json`'s format (writing to a `Vec` cannot fail).
fn write_json_value<T: Serialize + ?Sized>(out: &mut Vec<u8>, v: &T) {
    let _ = serde_json::to_writer(out, v);
}

/// Sorts an object's fields by key; of equal keys the last one stays (as a map insert would).
fn sorted(mut fields: Vec<(Cow<'static, str>, Node)>) -> Node {
    if !fields.is_sorted_by(|a, b| a.0 < b.0) {
        // stable: equal keys keep their order, and the last of each run is the one kept
        fields.sort_by(|a, b| a.0.cmp(&b.0));
        let mut kept: Vec<(Cow<'static, str>, Node)> = Vec::with_capacity(fields.len());
        for f in fields {
            match kept.last_mut() {
                Some(last) if last.0 == f.0 => *last = f,
                _ => kept.push(f),
            }
        }
        fields = kept;
    }
    Node::Obj(fields)
}

struct NodeSer;

/// A sequence or a tuple being built (and the variant it is under, if any).
struct SeqSer {
    items: Vec<Node>,
    variant: Option<&'static str>,
}

/// An object being built (and the variant it is under, if any; the key of a map entry
/// waiting for its value).
struct ObjSer {
    fields: Vec<(Cow<'static, str>, Node)>,
    variant: Option<&'static str>,
    key: Option<Cow<'static, str>>,
}

fn under(variant: Option<&'static str>, v: Node) -> Node {
    match variant {
        Some(name) => Node::Obj(vec![(Cow::Borrowed(name), v)]),
        None => v,
    }
}

impl ser::Serializer for NodeSer {
    type Ok = Node;
    type Error = NodeError;
    type SerializeSeq = SeqSer;
    type SerializeTuple = SeqSer;
    type SerializeTupleStruct = SeqSer;
    type SerializeTupleVariant = SeqSer;
    type SerializeMap = ObjSer;
    type SerializeStruct = ObjSer;
    type SerializeStructVariant = ObjSer;

    fn serialize_bool(self, v: bool) -> Result<Node, NodeError> {
        Ok(Node::Bool(v))
    }
    fn serialize_i8(self, v: i8) -> Result<Node, NodeError> {
        self.serialize_i64(v.into())
    }
    fn serialize_i16(self, v: i16) -> Result<Node, NodeError> {
        self.serialize_i64(v.into())
    }
    fn serialize_i32(self, v: i32) -> Result<Node, NodeError> {
        self.serialize_i64(v.into())
    }
    fn serialize_i64(self, v: i64) -> Result<Node, NodeError> {
        Ok(match u64::try_from(v) {
            Ok(u) => Node::U64(u),
            Err(_) => Node::I64(v),
        })
    }
    fn serialize_u8(self, v: u8) -> Result<Node, NodeError> {
        Ok(Node::U64(v.into()))
    }
    fn serialize_u16(self, v: u16) -> Result<Node, NodeError> {
        Ok(Node::U64(v.into()))
    }
    fn serialize_u32(self, v: u32) -> Result<Node, NodeError> {
        Ok(Node::U64(v.into()))
    }
    fn serialize_u64(self, v: u64) -> Result<Node, NodeError> {
        Ok(Node::U64(v))
    }
    fn serialize_f32(self, v: f32) -> Result<Node, NodeError> {
        self.serialize_f64(v.into())
    }
    fn serialize_f64(self, v: f64) -> Result<Node, NodeError> {
        Ok(if v.is_finite() {
            Node::F64(v)
        } else {
            Node::Null
        })
    }
    fn serialize_char(self, v: char) -> Result<Node, NodeError> {
        Ok(Node::Str(v.to_string()))
    }
    fn serialize_str(self, v: &str) -> Result<Node, NodeError> {
        Ok(Node::Str(v.to_string()))
    }
    fn serialize_bytes(self, v: &[u8]) -> Result<Node, NodeError> {
        Ok(Node::Arr(v.iter().map(|&b| Node::U64(b.into())).collect()))
    }
    fn serialize_none(self) -> Result<Node, NodeError> {
        Ok(Node::Null)
    }
    fn serialize_some<T: Serialize + ?Sized>(self, v: &T) -> Result<Node, NodeError> {
        v.serialize(self)
    }
    fn serialize_unit(self) -> Result<Node, NodeError> {
        Ok(Node::Null)
    }
    fn serialize_unit_struct(self, _name: &'static str) -> Result<Node, NodeError> {
        Ok(Node::Null)
    }
    fn serialize_unit_variant(
        self,
        _name: &'static str,
        _index: u32,
        variant: &'static str,
    ) -> Result<Node, NodeError> {
        Ok(Node::Str(variant.to_string()))
    }
    fn serialize_newtype_struct<T: Serialize + ?Sized>(
        self,
        _name: &'static str,
        v: &T,
    ) -> Result<Node, NodeError> {
        v.serialize(self)
    }
    fn serialize_newtype_variant<T: Serialize + ?Sized>(
        self,
        _name: &'static str,
        _index: u32,
        variant: &'static str,
        v: &T,
    ) -> Result<Node, NodeError> {
        Ok(under(Some(variant), v.serialize(self)?))
    }
    fn serialize_seq(self, len: Option<usize>) -> Result<SeqSer, NodeError> {
        Ok(SeqSer {
            items: Vec::with_capacity(len.unwrap_or(0)),
            variant: None,
        })
    }
    fn serialize_tuple(self, len: usize) -> Result<SeqSer, NodeError> {
        self.serialize_seq(Some(len))
    }
    fn serialize_tuple_struct(self, _name: &'static str, len: usize) -> Result<SeqSer, NodeError> {
        self.serialize_seq(Some(len))
    }
    fn serialize_tuple_variant(
        self,
        _name: &'static str,
        _index: u32,
        variant: &'static str,
        len: usize,
    ) -> Result<SeqSer, NodeError> {
        Ok(SeqSer {
            items: Vec::with_capacity(len),
            variant: Some(variant),
        })
    }
    fn serialize_map(self, len: Option<usize>) -> Result<ObjSer, NodeError> {
        Ok(ObjSer {
            fields: Vec::with_capacity(len.unwrap_or(0)),
            variant: None,
            key: None,
        })
    }
    fn serialize_struct(self, _name: &'static str, len: usize) -> Result<ObjSer, NodeError> {
        self.serialize_map(Some(len))
    }
    fn serialize_struct_variant(
        self,
        _name: &'static str,
        _index: u32,
        variant: &'static str,
        len: usize,
    ) -> Result<ObjSer, NodeError> {
        Ok(ObjSer {
            fields: Vec::with_capacity(len),
            variant: Some(variant),
            key: None,
        })
    }
}

impl SeqSer {
    fn element<T: Serialize + ?Sized>(&mut self, v: &T) -> Result<(), NodeError> {
        self.items.push(v.serialize(NodeSer)?);
        Ok(())
    }
    fn done(self) -> Result<Node, NodeError> {
        Ok(under(self.variant, Node::Arr(self.items)))
    }
}

/// serde's four sequence shapes for a builder `$ty` that is done as `$ok`, all built the same
/// way: an element goes to `$ty::element`, the end to `$ty::done` (here, and in
/// [`super::cells`]).
macro_rules! seq_shapes {
    ($ty:ty, $ok:ty) => {
        $crate::scene::row::seq_shapes!(@one $ty, $ok, SerializeSeq::serialize_element);
        $crate::scene::row::seq_shapes!(@one $ty, $ok, SerializeTuple::serialize_element);
        $crate::scene::row::seq_shapes!(@one $ty, $ok, SerializeTupleStruct::serialize_field);
        $crate::scene::row::seq_shapes!(@one $ty, $ok, SerializeTupleVariant::serialize_field);
    };
    (@one $ty:ty, $ok:ty, $tr:ident :: $method:ident) => {
        impl serde::ser::$tr for $ty {
            type Ok = $ok;
            type Error = $crate::scene::row::NodeError;
            fn $method<T: serde::Serialize + ?Sized>(
                &mut self,
                v: &T,
            ) -> Result<(), $crate::scene::row::NodeError> {
                self.element(v)
            }
            fn end(self) -> Result<$ok, $crate::scene::row::NodeError> {
                self.done()
            }
        }
    };
}
pub(crate) use seq_shapes;

seq_shapes!(SeqSer, Node);

/// A map key as `serde_json` writes it: a string, or a number or boolean as its text.
pub(crate) fn key_text(k: Node) -> Result<Cow<'static, str>, NodeError> {
    Ok(Cow::Owned(match k {
        Node::Str(s) => s,
        Node::U64(x) => x.to_string(),
        Node::I64(x) => x.to_string(),
        Node::Bool(b) => b.to_string(),
        Node::F64(x) => match serde_json::Number::from_f64(x) {
            Some(n) => n.to_string(),
            None => return Err(NodeError("a map key is not finite".into())),
        },
        _ => return Err(NodeError("a map key must be a string or a number".into())),
    }))
}

impl ObjSer {
    fn field<T: Serialize + ?Sized>(&mut self, key: &'static str, v: &T) -> Result<(), NodeError> {
        self.fields
            .push((Cow::Borrowed(key), v.serialize(NodeSer)?));
        Ok(())
    }

    fn done(self) -> Result<Node, NodeError> {
        Ok(under(self.variant, sorted(self.fields)))
    }
}

impl ser::SerializeMap for ObjSer {
    type Ok = Node;
    type Error = NodeError;
    fn serialize_key<T: Serialize + ?Sized>(&mut self, k: &T) -> Result<(), NodeError> {
        self.key = Some(key_text(k.serialize(NodeSer)?)?);
        Ok(())
    }
    fn serialize_value<T: Serialize + ?Sized>(&mut self, v: &T) -> Result<(), NodeError> {
        let k = self
            .key
            .take()
            .ok_or_else(|| NodeError("a map value without its key".into()))?;
        self.fields.push((k, v.serialize(NodeSer)?));
        Ok(())
    }
    fn end(self) -> Result<Node, NodeError> {
        self.done()
    }
}

/// serde's two struct shapes (plain and under a variant) for a builder `$ty` that is done as
/// `$ok`, built the same way: a field goes to `$ty::field`, the end to `$ty::done` (here, and in
/// [`super::cells`]).
macro_rules! struct_shapes {
    ($ty:ty, $ok:ty) => {
        $crate::scene::row::struct_shapes!(@one $ty, $ok, SerializeStruct);
        $crate::scene::row::struct_shapes!(@one $ty, $ok, SerializeStructVariant);
    };
    (@one $ty:ty, $ok:ty, $tr:ident) => {
        impl serde::ser::$tr for $ty {
            type Ok = $ok;
            type Error = $crate::scene::row::NodeError;
            fn serialize_field<T: serde::Serialize + ?Sized>(
                &mut self,
                key: &'static str,
                v: &T,
            ) -> Result<(), $crate::scene::row::NodeError> {
                self.field(key, v)
            }
            fn end(self) -> Result<$ok, $crate::scene::row::NodeError> {
                self.done()
            }
        }
    };
}
pub(crate) use struct_shapes;

struct_shapes!(ObjSer, Node);

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::BTreeMap;

    /// The reference: `serde_json`'s own path, through `Value`.
    fn via_value<T: Serialize>(v: &T) -> String {
        serde_json::to_string(&serde_json::to_value(v).expect("to_value")).expect("to_string")
    }

    fn via_node<T: Serialize>(v: &T) -> String {
        let mut out = Vec::new();
        Node::of(v).expect("node").write_json(&mut out);
        String::from_utf8(out).expect("utf-8")
    }

    #[derive(serde::Serialize)]
    enum Kind {
        Plain,
        Wrapped(f64),
        Pair(i32, f32),
        Named { z: u8, a: Option<f64> },
    }

    /// Fields out of key order, every kind of scalar, non-finite floats, nested objects and
    /// enum variants of each shape, a map with integer keys and one with a repeated key.
    #[derive(serde::Serialize)]
    struct Mixed {
        zeta: f64,
        alpha: i64,
        big: u64,
        nan: f64,
        inf: f64,
        tiny: f64,
        whole: f64,
        small: f32,
        letter: char,
        none: Option<f64>,
        some: Option<&'static str>,
        text: String,
        kinds: Vec<Kind>,
        by_int: BTreeMap<i32, f64>,
        #[serde(serialize_with = "repeated")]
        repeated: (),
        bytes: &'static [u8],
        unit: (),
        nested: Vec<Vec<f64>>,
        flag: bool,
    }

    /// A map whose key `b` comes twice (a map keeps the last), written out of order.
    fn repeated<S: serde::Serializer>(_: &(), s: S) -> Result<S::Ok, S::Error> {
        s.collect_map([("b", 1.0), ("a", 2.0), ("b", 3.0), ("\"q\\", 4.0)])
    }

    #[test]
    fn a_tree_is_written_as_its_value_is() {
        let m = Mixed {
            zeta: -0.1,
            alpha: -42,
            big: u64::MAX,
            nan: f64::NAN,
            inf: f64::NEG_INFINITY,
            tiny: 1e-300,
            whole: 3.0,
            small: 0.1,
            letter: 'é',
            none: None,
            some: Some("a \"quoted\"\nline"),
            text: "tab\there".into(),
            kinds: vec![
                Kind::Plain,
                Kind::Wrapped(2.5e10),
                Kind::Pair(-3, 1.5),
                Kind::Named {
                    z: 7,
                    a: Some(f64::INFINITY),
                },
            ],
            by_int: [(-1, 0.5), (10, 1.0), (2, 2.0)].into_iter().collect(),
            repeated: (),
            bytes: b"ab",
            unit: (),
            nested: vec![vec![], vec![1.0, -0.0]],
            flag: true,
        };
        assert_eq!(via_node(&m), via_value(&m));
    }

    #[test]
    fn cells_are_the_values_display() {
        for x in [0.1, -2.5e-17, 1e21, 3.0, f64::MAX, 5e-324] {
            let mut cell = Vec::new();
            assert!(Node::F64(x).cell(&mut cell));
            assert_eq!(cell, serde_json::json!(x).to_string().as_bytes());
        }
        let mut cell = Vec::new();
        assert!(!Node::Null.cell(&mut cell) && !Node::Str("x".into()).cell(&mut cell));
        assert!(Node::I64(-7).cell(&mut cell) && Node::Bool(false).cell(&mut cell));
        assert!(Node::U64(12).cell(&mut cell));
        assert_eq!(cell, b"-7false12");
    }

    #[test]
    fn every_scene_outcome_is_written_as_its_value_is() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
        let mut compared = 0;
        for entry in std::fs::read_dir(&dir).expect("scenes/") {
            let path = entry.expect("entry").path();
            if path.extension().and_then(|e| e.to_str()) != Some("toml") {
                continue;
            }
            let scene = crate::scene::load(&path).expect("a valid scene");
            match (scene.run(), scene.run_node()) {
                (Ok((value, _)), Ok(node)) => {
                    let mut out = Vec::new();
                    node.write_json(&mut out);
                    let expect = serde_json::to_string(&value).expect("to_string");
                    assert_eq!(String::from_utf8(out).expect("utf-8"), expect, "{path:?}");
                    assert_eq!(node, Node::from_value(&value), "{path:?}");
                    compared += 1;
                }
                (Err(a), Err(b)) => assert_eq!(a.to_string(), b.to_string(), "{path:?}"),
                (a, b) => panic!("{path:?}: {:?} against {:?}", a.is_ok(), b.is_ok()),
            }
        }
        assert!(compared >= 20, "{compared} scenes compared");
    }
}
