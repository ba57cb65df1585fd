//! Parquet output of batch and sweep results (`check --parquet FILE`), for data teams: polars
//! (the project's chosen dataframe library) behind the opt-in cargo feature `parquet`. The
//! default build has no polars; there `--parquet` is refused before anything runs.
//!
//! Columns: a batch has the columns of [`crate::report::batch::columns`] (SI units; text, f64
//! and u64 columns, nulls where a value does not apply), then `thickness_of`, `interface` and
//! `interface_<name>` for each of [`crate::report::batch::INTERFACE_COLUMNS`]. A film (or a scene
//! that could not be evaluated) is one row, its interface columns null (its interface's
//! stresses are the scene's `*_interface_*` columns); a layer stack is one row per interface,
//! top first (`interface` = 1 for the one below the top layer), each repeating the scene's
//! columns. This long form keeps one schema for every batch, whatever its deepest stack, so
//! files from several batches concatenate and every interface is filtered or grouped through
//! one column (`interface_bond_shear_utilisation`); the CSV's wide `interface<k>_*` columns
//! would need unpivoting first. Count scenes with `interface` null or 1. A sweep has one row
//! per thickness: `thickness_m`, the sweep quantities of `report::sweep` and `<check>_pass` for
//! the stress checks. Files are written by [`mod@crate::report::write`].

use crate::batch::SceneRun;
use crate::check::Evaluation;
use crate::error::Error;
use std::path::Path;

/// Whether this build writes Parquet.
pub const AVAILABLE: bool = cfg!(feature = "parquet");

/// The error for `--parquet` in a build without the feature.
pub fn unavailable() -> Error {
    Error::Value {
        origin: "--parquet".into(),
        msg: "this coatcheck was built without Parquet support; rebuild with `cargo build --release --features parquet`".into(),
    }
}

#[cfg(feature = "parquet")]
mod imp {
    use super::*;
    use crate::check::CheckKind;
    use crate::report::batch::{Cell, INTERFACE_COLUMNS, InterfaceRecord, Record, columns};
    use polars::prelude::{Column, DataFrame, ParquetWriter};

    /// One column's values.
    enum Data {
        Text(Vec<Option<String>>),
        Number(Vec<Option<f64>>),
        Count(Vec<u64>),
        Flag(Vec<Option<bool>>),
        Index(Vec<Option<u64>>),
    }

    impl Data {
        /// An empty column of the kind of `cell`.
        fn of(cell: Cell) -> Self {
            match cell {
                Cell::Text(_) => Data::Text(Vec::new()),
                Cell::Number(_) => Data::Number(Vec::new()),
                Cell::Count(_) => Data::Count(Vec::new()),
            }
        }

        /// A null: a value that does not apply to the row.
        fn push_null(&mut self) {
            match self {
                Data::Text(v) => v.push(None),
                Data::Number(v) => v.push(None),
                Data::Flag(v) => v.push(None),
                Data::Index(v) => v.push(None),
                Data::Count(_) => unreachable!("a count applies to every row"),
            }
        }

        fn push(&mut self, cell: Cell) {
            match (self, cell) {
                (Data::Text(v), Cell::Text(t)) => v.push(t),
                (Data::Number(v), Cell::Number(x)) => v.push(x),
                (Data::Count(v), Cell::Count(n)) => v.push(n),
                _ => unreachable!("a column's getter returns one kind of cell"),
            }
        }

        fn column(self, name: &str) -> Column {
            match self {
                Data::Text(v) => Column::new(name.into(), v),
                Data::Number(v) => Column::new(name.into(), v),
                Data::Count(v) => Column::new(name.into(), v),
                Data::Flag(v) => Column::new(name.into(), v),
                Data::Index(v) => Column::new(name.into(), v),
            }
        }
    }

    fn polars_error(path: &Path, e: impl std::fmt::Display) -> Error {
        Error::Io {
            path: path.to_path_buf(),
            source: std::io::Error::other(e.to_string()),
        }
    }

    fn write(path: &Path, height: usize, columns: Vec<Column>) -> Result<(), Error> {
        let mut df = DataFrame::new(height, columns).map_err(|e| polars_error(path, e))?;
        let mut failure = None;
        crate::report::write::write_bytes_with(path, |w| {
            ParquetWriter::new(w)
                .finish(&mut df)
                .map(|_| ())
                .map_err(|e| {
                    let io = std::io::Error::other(e.to_string());
                    failure = Some(e);
                    io
                })
        })
        .map_err(|e| failure.map_or(e, |f| polars_error(path, f)))
    }

    /// A row of a batch: a scene's record, and for a layer stack one of its interfaces with
    /// its index (from 1, top first).
    type Row<'a> = (&'a Record, Option<(u64, &'a InterfaceRecord)>);

    /// The rows of a batch (module docs): a stack once per interface, anything else once.
    fn rows(records: &[Record]) -> Vec<Row<'_>> {
        records
            .iter()
            .flat_map(|r| match r.interfaces.as_deref() {
                Some(interfaces) if !interfaces.is_empty() => interfaces
                    .iter()
                    .zip(1..)
                    .map(|(i, k)| (r, Some((k, i))))
                    .collect(),
                _ => vec![(r, None)],
            })
            .collect()
    }

    pub fn write_batch(path: &Path, runs: &[SceneRun]) -> Result<(), Error> {
        let records: Vec<Record> = runs.iter().map(Record::of).collect();
        let rows = rows(&records);
        let mut columns: Vec<Column> = columns()
            .iter()
            .map(|(name, get)| {
                let mut data = Data::of(get(&Record::default()));
                for (r, _) in &rows {
                    data.push(get(r));
                }
                data.column(name)
            })
            .collect();
        let thickness_of = rows.iter().map(|(r, _)| r.thickness_of.clone()).collect();
        columns.push(Data::Text(thickness_of).column("thickness_of"));
        let index = rows.iter().map(|(_, i)| i.map(|(k, _)| k)).collect();
        columns.push(Data::Index(index).column("interface"));
        for (name, get) in INTERFACE_COLUMNS {
            let mut data = Data::of(get(&Record::default(), &InterfaceRecord::default()));
            for (r, i) in &rows {
                match i {
                    Some((_, i)) => data.push(get(r, i)),
                    None => data.push_null(),
                }
            }
            columns.push(data.column(&format!("interface_{name}")));
        }
        write(path, rows.len(), columns)
    }

    pub fn write_sweep(path: &Path, rows: &[Evaluation]) -> Result<(), Error> {
        let mut columns = vec![Column::new(
            "thickness_m".into(),
            rows.iter()
                .map(|e| e.contact.thickness)
                .collect::<Vec<f64>>(),
        )];
        for (_, key, get) in crate::report::SWEEP {
            columns.push(Data::Number(rows.iter().map(get).collect()).column(key));
        }
        for kind in [CheckKind::BondShear, CheckKind::SubstrateYield] {
            let pass = rows
                .iter()
                .map(|e| e.checks.iter().find(|c| c.kind == kind).map(|c| c.pass))
                .collect();
            let name = format!("{}_pass", kind.name().replace('-', "_"));
            columns.push(Data::Flag(pass).column(&name));
        }
        write(path, rows.len(), columns)
    }
}

/// Write a batch as Parquet (one row per scene, a layer stack's per interface).
pub fn write_batch(path: &Path, runs: &[SceneRun]) -> Result<(), Error> {
    #[cfg(feature = "parquet")]
    return imp::write_batch(path, runs);
    #[cfg(not(feature = "parquet"))]
    {
        let _ = (path, runs);
        Err(unavailable())
    }
}

/// Write a thickness sweep as Parquet (one row per thickness).
pub fn write_sweep(path: &Path, rows: &[Evaluation]) -> Result<(), Error> {
    #[cfg(feature = "parquet")]
    return imp::write_sweep(path, rows);
    #[cfg(not(feature = "parquet"))]
    {
        let _ = (path, rows);
        Err(unavailable())
    }
}
