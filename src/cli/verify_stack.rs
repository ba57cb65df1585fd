//! `coatcheck verify MAP.csv --layer E,nu,d [--layer …] --substrate E,nu --pressure P`: the exact
//! contact on a layer stack (top first) beside Persson's theory on the stack from the map's
//! spectrum, at the top surface and at every interface; with `--friction μ` under sliding
//! ([`coatcheck::verify_stack::sliding`]): every interface's shear vector beside Persson's.
//!
//! Arguments to [`coatcheck::verify_stack::compare`]; the output is
//! [`coatcheck::report::verify_stack`]'s. Exit codes: 0 done (and no pixel's |τ| above
//! `--bond-strength` at any interface), 1 the bond strength is exceeded somewhere, 2 bad input
//! or a solve that did not converge (nothing is written then).

use super::response_stack::layer;
use super::verify::{FormatArg, Inputs, VerifyArgs, inputs, material};
use coatcheck::Error;
use coatcheck::layer::stack::Stack;
use coatcheck::prec::Settings;
use coatcheck::report::{
    self,
    verify_stack::{
        StackVerifyInputs, add_sliding_json, sliding_note, verify_csv, verify_json, verify_table,
        write_fields,
    },
};
use coatcheck::scene::Key;
use coatcheck::verify_stack::compare;
use coatcheck::verify_stack::sliding::compare_sliding;

/// Run `coatcheck verify --layer …`; returns the exit code or an error (exit code 2).
pub fn run(a: &VerifyArgs) -> Result<i32, Error> {
    let layers = a
        .layer
        .iter()
        .map(|l| layer(l))
        .collect::<Result<Vec<_>, _>>()?;
    let substrate = material("--substrate", &a.substrate, Key::SubstrateYoungsModulus)?;
    let stack = Stack::new(layers, substrate)?;
    let Inputs {
        p0,
        bond,
        settings,
        rtol,
        mu,
        map,
        boundary,
    } = inputs(a)?;
    let (c, sliding) = if mu > 0.0 {
        let s = compare_sliding(&map, &stack, (p0, mu), &settings, Settings { rtol }, bond)?;
        (s.comparison, Some((s.exact, s.persson)))
    } else {
        (
            compare(&map, &stack, p0, &settings, Settings { rtol }, bond)?,
            None,
        )
    };
    if let Some(path) = &a.fields {
        write_fields(path, &c.surface, &c.solution, &c.fields)?;
    }
    let names: Vec<String> = (1..=stack.layers().len())
        .map(|k| format!("layer {k}"))
        .collect();
    let inputs = StackVerifyInputs {
        map: &a.map,
        stack: &stack,
        names: &names,
        p0,
        bond,
        boundary,
    };
    let mut table = verify_table(&inputs, &c);
    if sliding.is_some() {
        table += &sliding_note(mu);
    }
    report::stdout(&match a.format {
        FormatArg::Table => table,
        FormatArg::Json => {
            // JSON shows NaN as null: the table of the same numbers is checked instead.
            report::finite_only(&table)?;
            let mut v = verify_json(&inputs, &c);
            if let Some((exact, persson)) = &sliding {
                add_sliding_json(&mut v, exact, persson);
            }
            format!(
                "{}\n",
                serde_json::to_string_pretty(&v).expect("a JSON value serialises")
            )
        }
        FormatArg::Csv => verify_csv(&inputs, &c),
    })?;
    let exceeded = c
        .interfaces
        .iter()
        .any(|i| i.above_bond.is_some_and(|f| f > 0.0));
    Ok(if exceeded { 1 } else { 0 })
}
