//! The derivations a formula reaches as `@name[k=v,...]`: the exact Galerkin integrals, the
//! Adomian series terms and the viscoelastic operator of 000, computed once per run.

use crate::algebra::poly::Q;
use crate::algebra::ratfunc::RatFunc;
use std::collections::BTreeMap;

/// The derivations `@name[...]` reaches, with their parameters and what they are.
pub const DERIVATIONS: &[(&str, &str, &str)] = &[
    (
        "taylor.STATE",
        "order (and the claim's `scene`, a text model)",
        "the Taylor polynomial at t = 0 of the text model's solution for STATE, to degree `order`, exact in its parameters as symbols (right sides polynomial in the states and t)",
    ),
    (
        "galerkin.bend",
        "m, n (odd)",
        "000 (2),(12): the projection of the bending term D~ Delta^2 w onto sin(m pi x/a) sin(n pi y/b), the coefficient of E~/(1-nu~^2)[f]",
    ),
    (
        "galerkin.load_sign",
        "m, n (odd)",
        "000 (2),(12): the sign sin(m pi/2) sin(n pi/2) with which the point load under the cone enters the projected equation",
    ),
    (
        "galerkin.airy_x",
        "m, n (odd)",
        "000 (3),(12): the coefficient of E~ f^2 cos(2 m pi x/a) in the Airy function solved from (3)",
    ),
    (
        "galerkin.airy_y",
        "m, n (odd)",
        "000 (3),(12): the coefficient of E~ f^2 cos(2 n pi y/b) in the Airy function solved from (3)",
    ),
    (
        "galerkin.a3",
        "m, n (odd)",
        "000 (2),(8),(12): the projected coefficient of f (in-plane loads p1, p2, Winkler Kw, Pasternak KG)",
    ),
    (
        "galerkin.ct",
        "m, n (odd)",
        "000 (2),(12): the projected coefficient of f' (the foundation damper CT)",
    ),
    (
        "galerkin.a4",
        "m, n (odd)",
        "000 (2),(12): the projected coefficient of f'' (inertia rho h)",
    ),
    (
        "galerkin.cubic",
        "m, n (odd)",
        "000 (2),(3),(12): the projected membrane coefficient of f E~[f^2], with the Airy function solved from (3)",
    ),
    (
        "series.a1",
        "",
        "000 (18)-(20): the second term a1(t) of the Adomian series, an exponential polynomial in t, with the viscous term d(z^2)/dt = 2 z z'",
    ),
    (
        "series.a1.zz",
        "",
        "000 (18)-(20): a1(t) with the viscous term z z' as printed in (18)",
    ),
    (
        "operator",
        "",
        "000 sec. 2: E~/(1-nu~^2) derived from E~ = E(1 + D/lambda) and a constant bulk modulus, as a rational function of D = d/dt",
    ),
    (
        "operator.constant",
        "",
        "000 sec. 2: the constant c of E~/(1-nu~^2) = c (1 + D/lambda)[L(alpha) - L(gamma)], from the partial fractions of @operator",
    ),
];

/// A reference `@name[k=v,...]` inside a derived formula.
#[derive(Clone, Debug)]
pub(super) struct DerivationRef {
    pub placeholder: String,
    pub name: String,
    pub params: Vec<(String, Q)>,
}

/// Splits the `@name[...]` references out of `text`, replacing each by a placeholder symbol.
pub(super) fn split_refs(text: &str) -> Result<(String, Vec<DerivationRef>), String> {
    let mut out = String::new();
    let mut refs = Vec::new();
    let mut rest = text;
    while let Some(at) = rest.find('@') {
        out.push_str(&rest[..at]);
        let after = &rest[at + 1..];
        let end = after
            .find(|ch: char| !(ch.is_ascii_alphanumeric() || ch == '_' || ch == '.'))
            .unwrap_or(after.len());
        let name = after[..end].to_string();
        let taylor = name
            .strip_prefix("taylor.")
            .is_some_and(|st| !st.is_empty() && !st.contains('.'));
        if !taylor && !DERIVATIONS.iter().any(|d| d.0 == name) {
            return Err(format!(
                "unknown derivation `@{name}`; known: {}",
                DERIVATIONS
                    .iter()
                    .map(|d| format!("@{}", d.0))
                    .collect::<Vec<_>>()
                    .join(", ")
            ));
        }
        let mut params = Vec::new();
        let mut tail = &after[end..];
        if let Some(inner) = tail.strip_prefix('[') {
            let close = inner
                .find(']')
                .ok_or_else(|| format!("`@{name}[`: no closing `]`"))?;
            for kv in inner[..close].split(',').filter(|s| !s.trim().is_empty()) {
                let (k, v) = kv
                    .split_once('=')
                    .ok_or_else(|| format!("`@{name}[{kv}]`: expected NAME=VALUE"))?;
                let v = crate::algebra::poly::parse_q(v)
                    .ok_or_else(|| format!("`@{name}[{kv}]`: `{v}` is not an exact number"))?;
                params.push((k.trim().to_string(), v));
            }
            tail = &inner[close + 1..];
        }
        let placeholder = format!("at_ref_{}", refs.len());
        out.push_str(&placeholder);
        refs.push(DerivationRef {
            placeholder,
            name,
            params,
        });
        rest = tail;
    }
    out.push_str(rest);
    Ok((out, refs))
}

/// The derivations computed in one run, kept for the claims that share them.
#[derive(Default)]
pub struct Derivations {
    galerkin: BTreeMap<(u32, u32), crate::algebra::galerkin::Galerkin>,
}

impl Derivations {
    /// The exponential polynomials in t (`@series.*`); `None` for a rational derivation.
    pub(super) fn expo(&self, r: &DerivationRef) -> Option<crate::algebra::expo::Expo> {
        use crate::algebra::series::{SeriesParams, Viscous, adomian_terms};
        let visc = match r.name.as_str() {
            "series.a1" => Viscous::TwoZZ,
            "series.a1.zz" => Viscous::ZZ,
            _ => return None,
        };
        Some(adomian_terms(&SeriesParams::symbolic(), 1, visc).remove(1))
    }

    pub(super) fn get(
        &mut self,
        r: &DerivationRef,
        defaults: &[(String, Q)],
    ) -> Result<RatFunc, String> {
        let param = |k: &str| -> Result<u32, String> {
            let v = r
                .params
                .iter()
                .chain(defaults)
                .find(|(n, _)| n == k)
                .map(|(_, v)| v.clone())
                .ok_or_else(|| format!("`@{}` needs `{k}` (e.g. @{}[m=1,n=1])", r.name, r.name))?;
            use num_traits::ToPrimitive;
            v.to_integer()
                .to_u32()
                .filter(|_| v.is_integer())
                .ok_or_else(|| format!("`@{}`: {k} = {v} is not a positive integer", r.name))
        };
        if let Some(part) = r.name.strip_prefix("galerkin.") {
            let (m, n) = (param("m")?, param("n")?);
            let g = match self.galerkin.entry((m, n)) {
                std::collections::btree_map::Entry::Occupied(e) => e.into_mut(),
                std::collections::btree_map::Entry::Vacant(e) => {
                    e.insert(crate::algebra::galerkin::derive(m, n).map_err(|e| e.to_string())?)
                }
            };
            let p = &g.parts;
            return Ok(match part {
                "load_sign" => RatFunc::from_q(Q::from_integer(g.load_sign.into())),
                "airy_x" => g.airy_derived.0.clone(),
                "airy_y" => g.airy_derived.1.clone(),
                "bend" => p.bend.clone(),
                "a3" => p.a3.clone(),
                "ct" => p.ct.clone(),
                "a4" => p.a4.clone(),
                _ => p.cubic.clone(),
            });
        }
        Ok(match r.name.as_str() {
            "operator" => crate::algebra::operator::derived_operator(),
            _ => crate::algebra::operator::derived_constant(),
        })
    }
}

/// Whether a reference is to an exponential polynomial in t (`@series.*`).
pub(super) fn is_expo(r: &DerivationRef) -> bool {
    r.name.starts_with("series.")
}
