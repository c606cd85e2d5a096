//! The vocabulary of quantities (`vocabulary.toml`, shipped with the tool; a user's own file
//! adds to it) and the two ways a paper's words name a quantity: a description after its
//! symbol ("$\rho$ is the density of the plate": [`Vocabulary::describe`]) and a phrase right
//! before it ("a ball of mass $m$": [`Vocabulary::before_symbol`]).
//!
//! Words are compared as tokens: lower case, in the singular ([`tokens`]). A description's
//! quantity is its head noun group (the words before the first preposition, an "of" phrase of
//! the vocabulary kept whole: "moment of inertia"), after its transparent words ("the disk
//! angular velocity vector", "the projection of the velocity"), and only when nothing in it
//! says it is another quantity: a quantity word before the head ("force density"), a word of
//! the entry's `unless`, or a scaling ("per unit", "referred to", "dimensionless").
//!
//! Written by hand: a few hundred phrases matched on tokens; a natural-language crate would
//! weigh more than the whole reader and still not know the vocabulary of mechanics.

use crate::algebra::units::Unit;
use serde::Deserialize;
use std::collections::BTreeMap;

/// The built-in vocabulary.
pub const BUILTIN: &str = include_str!("vocabulary.toml");

/// One quantity of the vocabulary.
#[derive(Clone, Debug, PartialEq)]
pub struct Quantity {
    /// Its name (the table's key: `mass`, `angular_velocity`).
    pub name: String,
    /// Its SI unit; `None` for a quantity whose unit its law fixes (a stiffness).
    pub unit: Option<Unit>,
    /// Words that, later in the same description, mean another quantity.
    pub unless: Vec<String>,
}

/// A phrase of the vocabulary: its quantity, and whether it names a symbol only in a
/// description ("$M$ is the moment", never "at the moment $t_1$").
#[derive(Clone, Debug, PartialEq)]
struct Phrase {
    quantity: usize,
    description_only: bool,
}

/// Quantities and the phrases that name them.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Vocabulary {
    quantities: Vec<Quantity>,
    phrases: BTreeMap<Vec<String>, Phrase>,
    longest: usize,
    /// The words that stand for the quantity they qualify (`[senses] qualifying`: "the
    /// amplitude of the applied force" is a force), in the singular.
    qualifying: Vec<String>,
}

/// The `[senses]` table of a vocabulary: how words take their sense from the words around them.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSenses {
    /// Words that stand for the quantity they qualify ("the velocity vector", "the amplitude
    /// of the force").
    #[serde(default)]
    qualifying: Vec<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawQuantity {
    words: Vec<String>,
    unit: Option<String>,
    #[serde(default)]
    unless: Vec<String>,
    #[serde(default)]
    description_only: Vec<String>,
}

/// What a phrase names: a quantity with its unit, and the phrase as matched.
#[derive(Clone, Debug, PartialEq)]
pub struct Hit<'a> {
    /// The quantity.
    pub quantity: &'a Quantity,
    /// The vocabulary's phrase that matched (`young's modulus`).
    pub phrase: String,
    /// Whether the words were in the plural ("the penetration depths").
    pub plural: bool,
}

/// Words that open a description without being part of it.
const DETERMINERS: &[&str] = &[
    "the", "a", "an", "its", "their", "his", "her", "this", "that", "these", "those", "each",
    "some", "our", "one", "both", "all",
];

/// Words that end a description's head noun group.
const BOUNDARY: &[&str] = &[
    "of",
    "between",
    "about",
    "on",
    "from",
    "in",
    "at",
    "with",
    "for",
    "to",
    "along",
    "around",
    "per",
    "by",
    "as",
    "which",
    "that",
    "when",
    "where",
    "whose",
    "due",
    "under",
    "over",
    "through",
    "into",
    "onto",
    "against",
    "during",
    "before",
    "after",
    "while",
    "if",
    "is",
    "are",
    "and",
    "or",
    "than",
    "respectively",
    "we",
    "it",
    "can",
    "may",
    "must",
    "will",
    "be",
    "was",
    "were",
    "has",
    "have",
];

/// Participles: after a noun they end its group ("the force applied to"), before one they
/// are adjectives ("the applied force").
const PARTICIPLES: &[&str] = &[
    "acting", "measured", "referred", "taken", "given", "caused", "exerted", "applied", "defined",
    "obtained",
];

/// Words that make a description another quantity than its head ("the force per unit length",
/// "the moment referred to the normal reaction", "the dimensionless time").
const SCALINGS: &[&[&str]] = &[
    &["per"],
    &["referred", "to"],
    &["divided", "by"],
    &["normalized"],
    &["normalised"],
    &["dimensionless"],
    &["nondimensional"],
    &["non-dimensional"],
    &["scaled"],
    &["reduced"],
    &["relative", "to", "the", "normal"],
    &["square"],
    &["squared"],
    &["logarithm"],
    &["inverse"],
    &["reciprocal"],
    &["ratio"],
];

/// A word in the singular, lower case ("Velocities" -> "velocity", "radii" -> "radius").
pub fn singular(word: &str) -> String {
    let w = word.to_lowercase();
    let irregular = [
        ("radii", "radius"),
        ("moduli", "modulus"),
        ("momenta", "momentum"),
        ("axes", "axis"),
        ("indices", "index"),
        ("vertices", "vertex"),
        ("matrices", "matrix"),
        ("series", "series"),
        ("analyses", "analysis"),
    ];
    if let Some((_, s)) = irregular.iter().find(|(p, _)| *p == w) {
        return (*s).to_string();
    }
    if let Some(stem) = w.strip_suffix("ies")
        && stem.len() > 1
    {
        return format!("{stem}y");
    }
    for end in ["sses", "shes", "ches", "xes", "zes"] {
        if w.ends_with(end) {
            return w[..w.len() - 2].to_string();
        }
    }
    if w.len() > 3 && w.ends_with('s') && !["ss", "us", "is", "'s"].iter().any(|e| w.ends_with(e)) {
        return w[..w.len() - 1].to_string();
    }
    w
}

/// The words of a text as tokens: letters, digits, `'` and `-` inside a word; each in the
/// singular; with whether it was plural.
pub fn tokens(text: &str) -> Vec<(String, bool)> {
    text.replace(['\u{2019}', '`'], "'")
        .split(|c: char| !(c.is_alphanumeric() || c == '\'' || c == '-'))
        .map(|w| w.trim_matches(|c| c == '\'' || c == '-'))
        .filter(|w| !w.is_empty())
        .map(|w| {
            let s = singular(w);
            let plural = s != w.to_lowercase();
            (s, plural)
        })
        .collect()
}

fn words_of(phrase: &str) -> Vec<String> {
    tokens(phrase).into_iter().map(|(w, _)| w).collect()
}

impl Vocabulary {
    /// The vocabulary shipped with the tool.
    pub fn builtin() -> Result<Vocabulary, String> {
        Self::parse(BUILTIN, "the built-in vocabulary")
    }

    /// Reads a vocabulary file; `origin` names it in errors (a bad unit, a phrase given twice,
    /// a key that is not `words`, `unit`, `unless` or `description_only`).
    pub fn parse(text: &str, origin: &str) -> Result<Vocabulary, String> {
        let mut table: toml::Table =
            toml::from_str(text).map_err(|e| format!("{origin}: {}", e.message()))?;
        let senses: Option<RawSenses> = table
            .remove("senses")
            .map(|t| t.try_into())
            .transpose()
            .map_err(|e: toml::de::Error| format!("{origin}: [senses]: {}", e.message()))?;
        let raw: BTreeMap<String, RawQuantity> = toml::Value::Table(table)
            .try_into()
            .map_err(|e: toml::de::Error| format!("{origin}: {}", e.message()))?;
        let mut v = Vocabulary {
            qualifying: senses
                .map(|s| s.qualifying.iter().map(|w| singular(w)).collect())
                .unwrap_or_default(),
            ..Vocabulary::default()
        };
        let mut seen: BTreeMap<Vec<String>, String> = BTreeMap::new();
        for (name, q) in raw {
            let unit = match &q.unit {
                Some(u) => Some(
                    Unit::parse(u).map_err(|m| format!("{origin}: [{name}] unit = {u:?}: {m}"))?,
                ),
                None => None,
            };
            if q.words.is_empty() {
                return Err(format!("{origin}: [{name}] has no words"));
            }
            let index = v.quantities.len();
            for w in &q.words {
                let key = words_of(w);
                if key.is_empty() {
                    return Err(format!("{origin}: [{name}] words: {w:?} has no word"));
                }
                if let Some(other) = seen.insert(key.clone(), name.clone()) {
                    return Err(format!(
                        "{origin}: the words {w:?} are given twice, in [{other}] and [{name}]"
                    ));
                }
                v.longest = v.longest.max(key.len());
                let description_only = q.description_only.iter().any(|d| words_of(d) == key);
                v.phrases.insert(
                    key,
                    Phrase {
                        quantity: index,
                        description_only,
                    },
                );
            }
            for d in &q.description_only {
                if !q.words.iter().any(|w| words_of(w) == words_of(d)) {
                    return Err(format!(
                        "{origin}: [{name}] description_only = {d:?} is not one of its words"
                    ));
                }
            }
            v.quantities.push(Quantity {
                name,
                unit,
                unless: q.unless.iter().map(|u| singular(u)).collect(),
            });
        }
        Ok(v)
    }

    /// This vocabulary with `other`'s quantities added; a phrase of both names `other`'s.
    pub fn extended(mut self, other: Vocabulary) -> Vocabulary {
        let offset = self.quantities.len();
        self.quantities.extend(other.quantities);
        for (k, p) in other.phrases {
            self.phrases.insert(
                k,
                Phrase {
                    quantity: p.quantity + offset,
                    ..p
                },
            );
        }
        self.longest = self.longest.max(other.longest);
        for w in other.qualifying {
            if !self.qualifying.contains(&w) {
                self.qualifying.push(w);
            }
        }
        self
    }

    /// Every quantity, in the file's order.
    pub fn quantities(&self) -> &[Quantity] {
        &self.quantities
    }

    /// The longest phrase at `toks[at..]`: its length and phrase.
    fn longest_at(&self, toks: &[String], at: usize) -> Option<(usize, &Phrase)> {
        (1..=self.longest.min(toks.len() - at))
            .rev()
            .find_map(|n| self.phrases.get(&toks[at..at + n]).map(|p| (n, p)))
    }

    /// The longest phrase that ends `toks`: where it starts, and the phrase.
    fn longest_suffix(&self, toks: &[String]) -> Option<(usize, &Phrase)> {
        let k = toks.len();
        (1..=self.longest.min(k))
            .rev()
            .find_map(|n| self.phrases.get(&toks[k - n..]).map(|p| (k - n, p)))
    }

    /// Whether a phrase of the vocabulary lies in `toks` (a quantity word before a head makes
    /// another quantity: "force density", "reaction momentum").
    fn holds_phrase(&self, toks: &[String]) -> bool {
        (0..toks.len()).any(|i| self.longest_at(toks, i).is_some())
    }

    fn hit(&self, toks: &[(String, bool)], start: usize, end: usize, p: &Phrase) -> Hit<'_> {
        Hit {
            quantity: &self.quantities[p.quantity],
            phrase: toks[start..end]
                .iter()
                .map(|(w, _)| w.as_str())
                .collect::<Vec<_>>()
                .join(" "),
            plural: toks[end - 1].1,
        }
    }

    /// The quantity a description names ("the relaxed Young's modulus", "the projections of the
    /// velocity of the centre of mass"), or `None` when its words do not fix one.
    pub fn describe(&self, text: &str) -> Option<Hit<'_>> {
        self.describe_tokens(&tokens(text), 0)
    }

    fn describe_tokens(&self, toks: &[(String, bool)], depth: usize) -> Option<Hit<'_>> {
        let words: Vec<String> = toks.iter().map(|(w, _)| w.clone()).collect();
        let n = words.len();
        let mut i = 0;
        while i < n && DETERMINERS.contains(&words[i].as_str()) {
            i += 1;
        }
        // the head noun group: up to the first boundary word, an "of" phrase kept whole
        let mut j = i;
        while j < n {
            if let Some((len, _)) = self.longest_at(&words, j)
                && words[j..j + len]
                    .iter()
                    .any(|w| BOUNDARY.contains(&w.as_str()))
            {
                j += len;
                continue;
            }
            // "relative to": a boundary; "the relative velocity": an adjective
            if BOUNDARY.contains(&words[j].as_str())
                || (PARTICIPLES.contains(&words[j].as_str())
                    || DETERMINERS.contains(&words[j].as_str()))
                    && j > i
                || words[j] == "relative" && words.get(j + 1).is_some_and(|w| w == "to")
            {
                break;
            }
            j += 1;
        }
        let group_end = j;
        // "is undergoing uniform circular motion": a verb, no description
        if group_end == i
            || i == 0 && words[0].ends_with("ing") && self.longest_at(&words, 0).is_none()
        {
            return None;
        }
        // the group's own phrase ("the relaxed Young's modulus"), else without its transparent
        // words ("the disk angular velocity vector"), else what they qualify ("the absolute
        // value of the tangential component of the velocity")
        // "the amplitude of the applied force" is a force, "the amplitude" alone a length
        let transparent = |w: &str| self.qualifying.iter().any(|q| q == w);
        if transparent(&words[group_end - 1])
            && depth < 4
            && words.get(group_end).is_some_and(|w| w == "of")
            && let Some(h) = self
                .describe_tokens(&toks[group_end + 1..], depth + 1)
                .filter(|h| h.quantity.unit.is_some())
        {
            return Some(h);
        }
        let mut k = group_end;
        if self.longest_suffix(&words[i..k]).is_none() {
            while k > i && transparent(&words[k - 1]) {
                k -= 1;
            }
            let stripped = k < group_end;
            if stripped
                && self.longest_suffix(&words[i..k]).is_none()
                && depth < 4
                && words.get(group_end).is_some_and(|w| w == "of")
            {
                return self
                    .describe_tokens(&toks[group_end + 1..], depth + 1)
                    .filter(|h| h.quantity.unit.is_some());
            }
            if k == i {
                k = group_end;
            }
        }
        let (start, phrase) = self.longest_suffix(&words[i..k])?;
        let start = i + start;
        let hit = self.hit(toks, start, k, phrase);
        if hit.quantity.unit.is_none()
            || self.holds_phrase(&words[i..start])
            || hit.quantity.unless.iter().any(|u| words[k..].contains(u))
            || scaled(&words[..start])
            || scaled(&words[k..])
        {
            return None;
        }
        Some(hit)
    }

    /// The quantity named by the words right before a symbol ("a ball of mass", "the stiffness",
    /// "with the dimensions"): the longest phrase that ends them, when nothing before it makes
    /// it another quantity.
    pub fn before_symbol(&self, text: &str) -> Option<Hit<'_>> {
        let toks = tokens(text);
        let words: Vec<String> = toks.iter().map(|(w, _)| w.clone()).collect();
        let (start, phrase) = self.longest_suffix(&words)?;
        let hit = self.hit(&toks, start, words.len(), phrase);
        let before = &words[..start];
        // a phrase right before the match makes another quantity ("the force density")
        let modifier = before
            .last()
            .is_some_and(|w| !DETERMINERS.contains(&w.as_str()) && !BOUNDARY.contains(&w.as_str()))
            && self.longest_suffix(before).is_some();
        if phrase.description_only || hit.quantity.unit.is_none() || modifier || scaled(before) {
            return None;
        }
        Some(hit)
    }
}

/// Whether `words` hold a scaling ("per unit", "dimensionless").
fn scaled(words: &[String]) -> bool {
    SCALINGS.iter().any(|s| {
        words
            .windows(s.len())
            .any(|w| w.iter().zip(*s).all(|(a, b)| a == b))
    })
}
