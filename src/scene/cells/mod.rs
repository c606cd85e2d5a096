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
/// strings of its top-level `warnings`, and, when the walk followed no plan, its [`Trail`],
/// which the next runs of the same model are given as their `plan`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Cells {
    /// One per column.
    pub leaves: Vec<Option<Leaf>>,
    /// The `warnings` strings, in order.
    pub warnings: Vec<String>,
    /// What the walk met, in order (recorded when it followed no plan).
    pub trail: Trail,
}

/// What a walk met, in order: each name, index and key it went into and out of, each leaf
/// with its column, each string with whether it was a warning. A later walk of the same model
/// that meets the same steps is on the same paths, so it follows the trail (a name compared
/// by its address, no path written, no column looked for); at the first step that differs
/// it writes out the path it is on and goes on as a walk without a plan.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Trail(Vec<Step>);

/// A step of a [`Trail`].
#[derive(Clone, Debug, PartialEq)]
enum Step {
    /// A struct's field or an enum's variant, by its name.
    Name(&'static str),
    /// A sequence's element.
    Index(usize),
    /// A map's entry, by its key's text.
    Key(String),
    /// Out of the last one gone into.
    Out,
    /// A leaf, to its column (`usize::MAX`: none).
    Leaf(usize),
    /// A string: a warning or not.
    Text(bool),
}

/// The cells of `v` under `cols`, following `plan` (the [`Trail`] of an earlier run of the
/// same model; an empty one to follow none): a plan that does not fit changes the time, never
/// the cells.
pub fn of<T: Serialize + ?Sized>(v: &T, cols: &[String], plan: &Trail) -> Result<Cells, NodeError> {
    let mut reuse = Reuse::default();
    fill(v, cols, plan, &mut reuse)?;
    Ok(reuse.cells)
}

/// The buffers of one walk after another (a sweep's run of points): each walk clears and
/// refills them, so a point allocates nothing for its cells.
#[derive(Debug, Default)]
pub struct Reuse {
    /// The cells of the last walk.
    pub cells: Cells,
    path: String,
    key: String,
}

/// [`of`], into `reuse`'s buffers: the cells are those [`of`] gives, in `reuse.cells`.
pub fn fill<'r, T: Serialize + ?Sized>(
    v: &T,
    cols: &[String],
    plan: &Trail,
    reuse: &'r mut Reuse,
) -> Result<&'r Cells, NodeError> {
    let Reuse { cells, path, key } = reuse;
    cells.leaves.clear();
    cells.leaves.resize(cols.len(), None);
    cells.warnings.clear();
    cells.trail.0.clear();
    path.clear();
    let mut w = Walk {
        cols,
        plan: &plan.0,
        at: if plan.0.is_empty() { OFF } else { 0 },
        record: plan.0.is_empty(),
        len: 0,
        path,
        key,
        cells,
    };
    v.serialize(&mut w)?;
    Ok(&reuse.cells)
}

/// The digits of `i` in decimal.
fn digits(i: usize) -> usize {
    i.checked_ilog10().map_or(1, |d| d as usize + 1)
}

/// Where a walk that is off its plan (or has none) is on it.
const OFF: usize = usize::MAX;

/// A walk: the columns, the plan and the index of its next step while the walk is on it
/// ([`OFF`]: off it, or none), whether to record the trail, and the path: its text, written
/// only off the plan, and its length, kept always (what a step out goes back to).
struct Walk<'c> {
    cols: &'c [String],
    plan: &'c [Step],
    at: usize,
    record: bool,
    len: usize,
    path: &'c mut String,
    key: &'c mut String,
    cells: &'c mut Cells,
}

impl Walk<'_> {
    /// Whether the plan's next step `fits` (the walk then moves past it); at the first that
    /// does not, the walk leaves the plan ([`Walk::off`]).
    #[inline(always)]
    fn on(&mut self, fits: impl FnOnce(&Step) -> bool) -> bool {
        if self.plan.get(self.at).is_some_and(fits) {
            self.at += 1;
            return true;
        }
        self.off();
        false
    }

    /// Leaves the plan, if on it: writes out the path the steps followed so far lead to.
    fn off(&mut self) {
        if self.at == OFF {
            return;
        }
        #[cfg(test)]
        tests::LEFT.with(|n| n.set(n.get() + 1));
        let plan = &self.plan[..self.at.min(self.plan.len())];
        self.at = OFF;
        let mut backs = Vec::new();
        self.path.clear();
        for s in plan {
            match s {
                Step::Name(t) => backs.push(push_segment(self.path, t)),
                Step::Key(t) => backs.push(push_segment(self.path, t)),
                Step::Index(i) => {
                    use std::fmt::Write as _;
                    backs.push(self.path.len());
                    let _ = write!(self.path, ".{i}");
                }
                Step::Out => self.path.truncate(backs.pop().unwrap_or(0)),
                Step::Leaf(_) | Step::Text(_) => {}
            }
        }
    }

    /// A number or a boolean: to its column.
    #[inline]
    fn leaf(&mut self, leaf: Leaf) {
        let mut at = None;
        if !self.on(|s| match s {
            Step::Leaf(i) => {
                at = Some(*i);
                true
            }
            _ => false,
        }) {
            // off the plan (or leaving it here): the column the path names
            at = self.cols.iter().position(|c| c == self.path.as_str());
        }
        if let Some(cell) = at.and_then(|i| self.cells.leaves.get_mut(i)) {
            *cell = Some(leaf);
        }
        if self.record {
            self.cells
                .trail
                .0
                .push(Step::Leaf(at.unwrap_or(usize::MAX)));
        }
    }

    /// A string: kept when it is an entry of the top-level `warnings`.
    fn text(&mut self, s: &str) {
        let mut kept = false;
        if !self.on(|s| match s {
            Step::Text(k) => {
                kept = *k;
                true
            }
            _ => false,
        }) {
            let entry = self.path.strip_prefix("warnings.");
            kept = entry.is_some_and(|i| !i.is_empty() && i.bytes().all(|b| b.is_ascii_digit()));
        }
        if kept {
            self.cells.warnings.push(s.to_string());
        }
        if self.record {
            self.cells.trail.0.push(Step::Text(kept));
        }
    }

    /// Into a struct's field or an enum's variant; returns the path's length to go back to.
    #[inline]
    fn enter(&mut self, name: &'static str) -> usize {
        let len = self.len;
        // the same name: at the same address (one name of the program), or of the same text
        if self.on(|s| matches!(s, Step::Name(n) if std::ptr::eq(*n, name) || *n == name)) {
            self.len += usize::from(len > 0) + name.len();
        } else {
            push_segment(self.path, name);
            self.len = self.path.len();
        }
        if self.record {
            self.cells.trail.0.push(Step::Name(name));
        }
        len
    }

    /// Into a map's entry, by the key's text in `self.key`.
    fn enter_key(&mut self) -> usize {
        let len = self.len;
        let key = std::mem::take(self.key);
        if self.on(|s| matches!(s, Step::Key(k) if *k == key)) {
            self.len += usize::from(len > 0) + key.len();
        } else {
            push_segment(self.path, &key);
            self.len = self.path.len();
        }
        if self.record {
            self.cells.trail.0.push(Step::Key(key.clone()));
        }
        *self.key = key;
        len
    }

    /// Into a sequence's element.
    fn enter_index(&mut self, i: usize) -> usize {
        let len = self.len;
        if self.on(|s| *s == Step::Index(i)) {
            self.len += 1 + digits(i);
        } else {
            use std::fmt::Write as _;
            let _ = write!(self.path, ".{i}");
            self.len = self.path.len();
        }
        if self.record {
            self.cells.trail.0.push(Step::Index(i));
        }
        len
    }

    /// Out of what was gone into at path length `len`.
    #[inline]
    fn leave(&mut self, len: usize) {
        if !self.on(|s| *s == Step::Out) {
            self.path.truncate(len);
        }
        self.len = len;
        if self.record {
            self.cells.trail.0.push(Step::Out);
        }
    }
}

/// Appends a segment to a path (after a `.` unless it is the first); returns the length
/// before.
fn push_segment(path: &mut String, segment: &str) -> usize {
    let len = path.len();
    if len > 0 {
        path.push('.');
    }
    path.push_str(segment);
    len
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
        self.w.leave(len);
        Ok(())
    }

    fn field<T: Serialize + ?Sized>(&mut self, key: &'static str, v: &T) -> Result<(), NodeError> {
        let len = self.w.enter(key);
        v.serialize(&mut *self.w)?;
        self.w.leave(len);
        Ok(())
    }

    fn done(self) -> Result<(), NodeError> {
        if let Some(len) = self.back {
            self.w.leave(len);
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
        self.leave(len);
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
    /// The key's text into the walk's key buffer: a string written there straight (no node, no
    /// string made per key: the text model's outcome has a dozen), any other through its
    /// [`Node`].
    fn serialize_key<T: Serialize + ?Sized>(&mut self, k: &T) -> Result<(), NodeError> {
        self.w.key.clear();
        if k.serialize(KeyStr(self.w.key)).is_err() {
            self.w.key.clear();
            self.w.key.push_str(&key_text(Node::of(k)?)?);
        }
        self.key = Some(self.w.enter_key());
        Ok(())
    }
    fn serialize_value<T: Serialize + ?Sized>(&mut self, v: &T) -> Result<(), NodeError> {
        let len = self
            .key
            .take()
            .ok_or_else(|| NodeError("a map value without its key".into()))?;
        v.serialize(&mut *self.w)?;
        self.w.leave(len);
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
mod tests;
