//! Reading an `ode` scene: its tables, in named steps, into a compiled [`OdeScene`].

use super::compile::Program;
use super::formulas::{Reader, table_of};
use super::outcomes::read_outcomes;
use super::units::read_units;
use super::{Compiled, EventSpec, MAX_VARS, OdeScene};
use crate::algebra::expr::Expr;
use crate::integrate::{Direction, Method};
use crate::models::params::{Fields, SceneError};
use std::collections::BTreeMap;
use toml::Value;

#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct RawScene {
    model: Option<Value>,
    parameters: Option<Value>,
    units: Option<Value>,
    definitions: Option<Value>,
    state: Option<Value>,
    equations: Option<Value>,
    event: Option<Value>,
    outcome: Option<Value>,
    solve: Option<Value>,
}

#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct RawEvent {
    name: Option<Value>,
    when: Option<Value>,
    direction: Option<Value>,
    action: Option<Value>,
    jump: Option<Value>,
    stop_after: Option<Value>,
}

/// The tables of an `ode` scene; `[definitions]` and `[outcome]` may be absent (empty).
struct Tables<'t> {
    params: &'t toml::Table,
    units: &'t toml::Table,
    state: &'t toml::Table,
    equations: &'t toml::Table,
    definitions: &'t toml::Table,
    outcome: &'t toml::Table,
}

static EMPTY: std::sync::LazyLock<toml::Table> = std::sync::LazyLock::new(toml::Table::new);

impl<'t> Tables<'t> {
    fn of(f: &Fields, raw: &'t RawScene) -> Result<Self, SceneError> {
        let optional = |v: Option<&'t Value>, name: &str| match v {
            None => Ok(&*EMPTY),
            v => table_of(f, v, name),
        };
        Ok(Tables {
            params: table_of(f, raw.parameters.as_ref(), "parameters")?,
            units: table_of(f, raw.units.as_ref(), "units")?,
            state: table_of(f, raw.state.as_ref(), "state")?,
            equations: table_of(f, raw.equations.as_ref(), "equations")?,
            definitions: optional(raw.definitions.as_ref(), "definitions")?,
            outcome: optional(raw.outcome.as_ref(), "outcome")?,
        })
    }
}

/// Reads and compiles an `ode` scene: the tables, the parameters, the states with their
/// equations, the units, the definitions, the initial values, the equations and their Jacobian,
/// the events and the outcomes, each checked before the next is read.
pub(super) fn read(root: &toml::Table, path: &str) -> Result<OdeScene, SceneError> {
    let f = Fields { path };
    let raw: RawScene = f.raw(root, "")?;
    let _ = raw.model;
    let t = Tables::of(&f, &raw)?;
    let params = read_parameters(&f, t.params)?;
    let states = read_states(&f, t.state, t.equations, &params)?;
    let slots = slots(&f, &states, &params)?;
    let units = read_units(&f, t.units, &slots)?;
    let mut r = Reader {
        f,
        units,
        def_units: BTreeMap::new(),
        raw: Default::default(),
        defs: BTreeMap::new(),
        slots,
    };
    read_definitions(&mut r, t.definitions)?;
    let (init, init_exprs) = read_initial(&r, t.state, &states, &params)?;
    let rhs_exprs = read_equations(&r, t.equations, &states)?;
    let (held, switches) = hold_switches(&mut r, &rhs_exprs, &states)?;
    let rhs = held
        .iter()
        .zip(&states)
        .map(|(e, s)| r.compile(e, &format!("equations.{s}")))
        .collect::<Result<Vec<_>, _>>()?;
    let solve = r.f.solve(raw.solve.as_ref(), "", false)?;
    let t_end = solve.t_end.ok_or_else(|| SceneError::Missing {
        path: path.into(),
        field: "solve.t_end".into(),
        allowed: "a time > 0 in s (an event with action = \"stop\" may end the run sooner)".into(),
    })?;
    let jac = if matches!(solve.method, Method::Radau5 | Method::Auto) {
        Some(r.jacobian(&held, &states)?)
    } else {
        None
    };
    let events = read_events(&r, raw.event.as_ref(), &states)?;
    let outcomes = read_outcomes(&r, t.outcome, &events)?;
    let event_names = events.iter().map(|e| e.name.to_string()).collect();
    let state_units: std::sync::Arc<BTreeMap<String, String>> = std::sync::Arc::new(
        states
            .iter()
            .map(|s| (s.clone(), r.units[s].to_string()))
            .collect(),
    );
    let outcome_units = std::sync::Arc::new(
        outcomes
            .iter()
            .map(|o| (o.name.to_string(), o.unit_text.clone()))
            .collect(),
    );
    let n = states.len();
    Ok(OdeScene {
        c: std::sync::Arc::new(Compiled {
            states,
            param_names: params.iter().map(|(p, _)| p.clone()).collect(),
            init,
            rhs,
            jac,
            events,
            switches,
            event_names,
            outcomes,
            state_units,
            outcome_units,
            t_end,
            init_exprs,
            rhs_exprs,
        }),
        params: params.iter().map(|(_, v)| *v).collect(),
        init_set: smallvec::smallvec![None; n],
        solve,
    })
}

/// Whether `n` may name a parameter, state or definition: letters, digits and _, not `t`, `pi`,
/// `hits` or a word of the calculus (`diff`, `int`, `at`, `sum`). A function's name may (a
/// paper's `gamma` or `beta`): in a formula it is a call only before `(`.
fn name_ok(n: &str) -> bool {
    n.chars()
        .next()
        .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && n.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
        && !matches!(n, "t" | "pi" | "hits" | "diff" | "int" | "at" | "sum")
}

/// `[parameters]`: each name with its value (SI).
fn read_parameters(f: &Fields, table: &toml::Table) -> Result<Vec<(String, f64)>, SceneError> {
    let mut params = Vec::new();
    for (k, v) in table {
        let field = format!("parameters.{k}");
        if !name_ok(k) {
            return Err(f.out_of_range(
                &field,
                k.clone(),
                "a name of letters, digits and _ (not t, pi, hits, diff, int, at or sum)",
            ));
        }
        params.push((
            k.clone(),
            f.num(Some(v), &field, None, |_| true, "a finite number (SI)")?,
        ));
    }
    Ok(params)
}

/// The states, in the order of `[state]`, each with its equation in `[equations]` and no
/// equation for anything else.
fn read_states(
    f: &Fields,
    state: &toml::Table,
    equations: &toml::Table,
    params: &[(String, f64)],
) -> Result<Vec<String>, SceneError> {
    let states: Vec<String> = state.keys().cloned().collect();
    if states.is_empty() {
        return Err(SceneError::Missing {
            path: f.path.into(),
            field: "state".into(),
            allowed: "at least one state with its initial value".into(),
        });
    }
    for s in &states {
        if !name_ok(s) || params.iter().any(|(p, _)| p == s) {
            return Err(f.out_of_range(
                &format!("state.{s}"),
                s.clone(),
                "a name of letters, digits and _, not a parameter's, not t, pi, hits, diff, int, at or sum",
            ));
        }
        if !equations.contains_key(s) {
            return Err(SceneError::Missing {
                path: f.path.into(),
                field: format!("equations.{s}"),
                allowed: format!("the derivative of the state {s}, a formula"),
            });
        }
    }
    if let Some(k) = equations.keys().find(|k| !states.contains(k)) {
        return Err(f.out_of_range(
            &format!("equations.{k}"),
            k.clone(),
            &format!(
                "an equation for each state of [state]: {}",
                states.join(", ")
            ),
        ));
    }
    Ok(states)
}

/// The variables every program reads, in their order: `t`, the states, the parameters; at most
/// [`MAX_VARS`].
fn slots(
    f: &Fields,
    states: &[String],
    params: &[(String, f64)],
) -> Result<Vec<String>, SceneError> {
    let mut slots = vec!["t".to_string()];
    slots.extend(states.iter().cloned());
    slots.extend(params.iter().map(|(p, _)| p.clone()));
    if slots.len() > MAX_VARS {
        return Err(f.out_of_range(
            "parameters",
            format!("{} states and parameters", slots.len() - 1),
            &format!("at most {} states and parameters", MAX_VARS - 1),
        ));
    }
    Ok(slots)
}

/// `[definitions]`, in any order: each read after the definitions it uses (a topological
/// order; among those free to go, the order of the file), a cycle an error naming its members.
fn read_definitions(r: &mut Reader, table: &toml::Table) -> Result<(), SceneError> {
    let mut uses: Vec<(&String, &Value, Vec<String>)> = Vec::new();
    for (k, v) in table {
        let field = format!("definitions.{k}");
        if !name_ok(k) || r.slots.contains(k) {
            return Err(r.bad(
                &field,
                k,
                "a new name (not a parameter or state; not t, pi, hits, diff, int, at or sum)",
            ));
        }
        // the names it uses, read before any definition is expanded (a formula that does not
        // parse is reported when its turn comes)
        let names = match v {
            Value::String(text) => crate::algebra::expr::parse(text)
                .map(|e| {
                    e.symbols()
                        .into_iter()
                        .filter(|s| table.contains_key(s))
                        .collect()
                })
                .unwrap_or_default(),
            _ => Vec::new(),
        };
        uses.push((k, v, names));
    }
    while !uses.is_empty() {
        let Some(i) = uses
            .iter()
            .position(|(_, _, names)| names.iter().all(|n| r.defs.contains_key(n)))
        else {
            let mut members: Vec<&str> = uses.iter().map(|(k, _, _)| k.as_str()).collect();
            members.retain(|m| {
                uses.iter()
                    .any(|(_, _, names)| names.iter().any(|n| n == m))
            });
            return Err(r.bad(
                &format!("definitions.{}", members[0]),
                &members.join(", "),
                &format!(
                    "definitions that do not use each other in a cycle; these do: {}",
                    members.join(", ")
                ),
            ));
        };
        let (k, v, _) = uses.remove(i);
        let field = format!("definitions.{k}");
        let (e, text) = r.formula_text(v, &field)?;
        let u = r.unit_of(&e, &field, &text)?;
        r.def_units.insert(k.clone(), u);
        r.defs.insert(k.clone(), e);
    }
    Ok(())
}

/// The right sides with each `sign` of a state read from a held value ([`super::switch`]), and
/// the switches; the right sides as written when a switch has no symbolic derivative.
fn hold_switches(
    r: &mut Reader,
    rhs: &[Expr],
    states: &[String],
) -> Result<(Vec<Expr>, Vec<super::switch::Switch>), SceneError> {
    let mut args = Vec::new();
    let held: Vec<Expr> = rhs
        .iter()
        .map(|e| super::switch::hold(e, states, &mut args))
        .collect();
    if args.is_empty() {
        return Ok((held, Vec::new()));
    }
    if r.slots.len() + args.len() > MAX_VARS {
        return Ok((rhs.to_vec(), Vec::new()));
    }
    let before = r.slots.len();
    r.slots
        .extend((0..args.len()).map(super::switch::held_name));
    match r.switches(&args, &held, states) {
        Some(sw) => Ok((held, sw)),
        None => {
            r.slots.truncate(before);
            Ok((rhs.to_vec(), Vec::new()))
        }
    }
}

/// `[state]`: each initial value, a formula of the parameters in its state's unit, compiled and
/// as a formula.
fn read_initial(
    r: &Reader,
    table: &toml::Table,
    states: &[String],
    params: &[(String, f64)],
) -> Result<(Vec<Program>, Vec<Expr>), SceneError> {
    let mut init = Vec::new();
    let mut init_exprs = Vec::new();
    for s in states {
        let field = format!("state.{s}");
        let (e, text) = r.formula_text(&table[s], &field)?;
        // a number is a value in the state's unit (`y = 1.0` for a state in m)
        let number = matches!(table[s], Value::Float(_) | Value::Integer(_));
        if let Some(x) = e
            .symbols()
            .into_iter()
            .find(|x| !params.iter().any(|(p, _)| p == x))
        {
            return Err(r.bad_formula(&field, &text, format!("an initial value is a number or a formula of the parameters; `{x}` is not a parameter")));
        }
        if !number {
            r.unit_is(
                &e,
                &field,
                &text,
                r.units[s],
                &format!("the initial value of {s}"),
            )?;
        }
        init.push(r.compile(&e, &field)?);
        init_exprs.push(e);
    }
    Ok((init, init_exprs))
}

/// `[equations]`: each right side, in its state's unit per the unit of t.
fn read_equations(
    r: &Reader,
    table: &toml::Table,
    states: &[String],
) -> Result<Vec<Expr>, SceneError> {
    let ut = r.units["t"];
    let mut rhs_exprs = Vec::new();
    for s in states {
        let field = format!("equations.{s}");
        let (e, text) = r.formula_text(&table[s], &field)?;
        let want = r.units[s].per(ut);
        r.unit_is(
            &e,
            &field,
            &text,
            want,
            &format!("d{s}/dt (the unit of {s} per the unit of t)"),
        )?;
        rhs_exprs.push(e);
    }
    Ok(rhs_exprs)
}

/// `[[event]]`: each event's name (unique), `when`, direction, action and jump, compiled.
fn read_events(
    r: &Reader,
    v: Option<&Value>,
    states: &[String],
) -> Result<Vec<EventSpec>, SceneError> {
    let mut events = Vec::new();
    let Some(v) = v else {
        return Ok(events);
    };
    let list = v
        .as_array()
        .ok_or_else(|| r.bad("event", &v.to_string(), "[[event]] tables"))?;
    for (i, ev) in list.iter().enumerate() {
        // an event is named in messages by its name, when it has a usable one
        let at = match ev.get("name").and_then(Value::as_str) {
            Some(n) if name_ok(&n.replace('-', "_")) => format!("event.{n}"),
            _ => format!("event.{i}"),
        };
        let event = read_event(r, &at, ev, states, &events)?;
        events.push(event);
    }
    Ok(events)
}

/// One `[[event]]` table, at `at` (`event.3`), after the events `earlier`.
fn read_event(
    r: &Reader,
    at: &str,
    ev: &Value,
    states: &[String],
    earlier: &[EventSpec],
) -> Result<EventSpec, SceneError> {
    let path = r.f.path;
    let t = ev
        .as_table()
        .ok_or_else(|| r.bad(at, &ev.to_string(), "a table"))?;
    let re: RawEvent = r.f.raw(t, at)?;
    let name = match &re.name {
        Some(Value::String(s)) if !s.is_empty() && !s.contains(['@', '[', ']']) => s.clone(),
        Some(other) => {
            return Err(r.bad(
                &format!("{at}.name"),
                &other.to_string(),
                "a name (no @, [ or ])",
            ));
        }
        None => {
            return Err(SceneError::Missing {
                path: path.into(),
                field: format!("{at}.name"),
                allowed: "the event's name, e.g. \"contact-end\"".into(),
            });
        }
    };
    if earlier.iter().any(|e| e.name == name) {
        return Err(r.bad(&format!("{at}.name"), &name, "a name no other event has"));
    }
    let when_v = re.when.as_ref().ok_or_else(|| SceneError::Missing {
        path: path.into(),
        field: format!("{at}.when"),
        allowed: "a formula whose root is the event".into(),
    })?;
    let (when, text) = r.formula_text(when_v, &format!("{at}.when"))?;
    r.unit_of(&when, &format!("{at}.when"), &text)?;
    let dir = r.f.choice(
        re.direction.as_ref(),
        &format!("{at}.direction"),
        &["up", "down", "any"],
        "any",
    )?;
    let direction = match dir.as_str() {
        "up" => Direction::Rising,
        "down" => Direction::Falling,
        _ => Direction::Both,
    };
    let action = r.f.choice(
        re.action.as_ref(),
        &format!("{at}.action"),
        &["stop", "record"],
        "record",
    )?;
    let mut jump = Vec::new();
    if let Some(j) = &re.jump {
        let jt = j.as_table().ok_or_else(|| {
            r.bad(
                &format!("{at}.jump"),
                &j.to_string(),
                "a table of state updates, { v = \"-e*v\" }",
            )
        })?;
        for (s, formula) in jt {
            let field = format!("{at}.jump.{s}");
            let k = states
                .iter()
                .position(|x| x == s)
                .ok_or_else(|| r.bad(&field, s, &format!("a state: {}", states.join(", "))))?;
            let (e, text) = r.formula_text(formula, &field)?;
            r.unit_is(
                &e,
                &field,
                &text,
                r.units[s],
                &format!("the new value of {s}"),
            )?;
            jump.push((k, r.compile(&e, &field)?));
        }
    }
    let stop_after = match &re.stop_after {
        None => None,
        Some(Value::Integer(n)) if *n >= 1 => Some(*n as usize),
        Some(other) => {
            return Err(r.bad(
                &format!("{at}.stop_after"),
                &other.to_string(),
                "an integer >= 1: the run stops at this firing",
            ));
        }
    };
    Ok(EventSpec {
        stop_after,
        name: name.into(),
        when: r.compile(&when, &format!("{at}.when"))?,
        direction,
        stop: action == "stop",
        jump,
    })
}
