//! The `ode` model's reference (`impact describe ode`).

use crate::models::doc as d;

/// The `ode` model's reference (`impact describe ode`).
pub const DOC: d::ModelDoc = d::ModelDoc {
    name: "ode",
    summary: "Any model as text: a paper's equations of motion written in the scene (parameters, units, states, equations, events with impact maps, outcomes), integrated like a built-in model. Units are checked equation by equation before anything runs; formulas are compiled once to flat programs; Radau5's Jacobian is their symbolic derivative. The format is in the module doc of src/models/ode/mod.rs.",
    conventions: &[
        "the signs and axes are the scene's own: the formulas say them",
        "an outcome `formula@event` is evaluated where the event fires, before its jump; `@event[k]` at its k-th firing (from 1), `@event[last]` at its last; `hits@event` counts firings; an event that never fired gives null and a warning",
        "a literal 0 has every unit (`max(z, 0)`)",
    ],
    example: "scenes/hertz_ode.toml",
    keys: &[&[
        d::Key {
            key: "model",
            unit: "-",
            range: "\"ode\"",
            default: "required",
            meaning: "the model",
        },
        d::Key {
            key: "parameters.*",
            unit: "as [units] says",
            range: "finite numbers; names of letters, digits and _ (not t, pi, hits or a function)",
            default: "required",
            meaning: "the parameters",
        },
        d::Key {
            key: "units.*",
            unit: "-",
            range: "a unit of SI names (\"N/m^1.5\", \"m/s\", \"1\") for every parameter, state and t",
            default: "required",
            meaning: "the unit of each name",
        },
        d::Key {
            key: "definitions.*",
            unit: "derived",
            range: "formulas of t, the states, the parameters and earlier definitions",
            default: "none",
            meaning: "named formulas, expanded where used",
        },
        d::Key {
            key: "state.*",
            unit: "as [units] says",
            range: "numbers or formulas of the parameters",
            default: "required (at least one)",
            meaning: "the states, in order, with their initial values",
        },
        d::Key {
            key: "equations.*",
            unit: "state per t",
            range: "a formula for each state: its derivative",
            default: "required",
            meaning: "the equations of motion",
        },
        d::Key {
            key: "event[].name",
            unit: "-",
            range: "unique, no @ [ ]",
            default: "required",
            meaning: "the event's name",
        },
        d::Key {
            key: "event[].when",
            unit: "any",
            range: "a formula",
            default: "required",
            meaning: "the event fires where it crosses zero",
        },
        d::Key {
            key: "event[].direction",
            unit: "-",
            range: "\"up\", \"down\", \"any\"",
            default: "\"any\"",
            meaning: "which crossings count",
        },
        d::Key {
            key: "event[].action",
            unit: "-",
            range: "\"stop\", \"record\"",
            default: "\"record\"",
            meaning: "stop the run there, or record it and go on",
        },
        d::Key {
            key: "event[].jump.*",
            unit: "the state's",
            range: "formulas, evaluated in the state before the jump",
            default: "none",
            meaning: "state updates where it fires: an impact map (at most 100,000 jumps per run)",
        },
        d::Key {
            key: "outcome.*",
            unit: "derived",
            range: "formula, formula@event, formula@event[k], formula@event[last], hits@event",
            default: "none",
            meaning: "named results",
        },
        d::Key {
            key: "solve.rtol",
            unit: "1",
            range: "0 < rtol < 1",
            default: "1e-9",
            meaning: "relative tolerance",
        },
        d::Key {
            key: "solve.atol",
            unit: "as the states",
            range: "atol > 0",
            default: "1e-12",
            meaning: "absolute tolerance",
        },
        d::Key {
            key: "solve.method",
            unit: "-",
            range: "\"dop853\", \"dopri5\", \"radau5\", \"auto\"",
            default: "\"dop853\"",
            meaning: "the integrator (Radau5 with the symbolic Jacobian)",
        },
        d::Key {
            key: "solve.t_end",
            unit: "s",
            range: "a time > 0",
            default: "required",
            meaning: "the end of the run (an event with action = \"stop\" may end it sooner)",
        },
    ]],
    outcomes: &[
        d::COMMON,
        &[
            d::Out {
                path: "outcome.*",
                unit: "outcome_units.*",
                meaning: "the named outcomes (null: its event never fired)",
            },
            d::Out {
                path: "outcome_units.*",
                unit: "-",
                meaning: "each outcome's unit, derived from its formula and [units]",
            },
            d::Out {
                path: "state.*",
                unit: "state_units.*",
                meaning: "the states at the end",
            },
            d::Out {
                path: "state_units.*",
                unit: "-",
                meaning: "each state's unit",
            },
            d::Out {
                path: "event_counts.*",
                unit: "-",
                meaning: "how many times each event fired",
            },
            d::Out {
                path: "stopped_by",
                unit: "-",
                meaning: "the event that stopped the run, or null",
            },
            d::Out {
                path: "t_end",
                unit: "s",
                meaning: "where the run ended",
            },
            d::Out {
                path: "jumps",
                unit: "-",
                meaning: "jumps applied",
            },
            d::Out {
                path: "method",
                unit: "-",
                meaning: "the integrator",
            },
            d::Out {
                path: "state_size",
                unit: "-",
                meaning: "states integrated",
            },
            d::Out {
                path: "warnings",
                unit: "-",
                meaning: "what the user should know",
            },
        ],
        d::STATS,
    ],
};
