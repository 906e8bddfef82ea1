//! What passes between Python and the numerics: errors raised as `flexmodes.errors` classes
//! with their data, work run with the GIL released (and a progress callback), and NumPy
//! arrays in and out.

use std::{
    str::FromStr,
    sync::{
        Mutex,
        atomic::{AtomicBool, Ordering},
    },
    time::Duration,
};

use faer::MatRef;
use flexmodes::{
    Error, Progress,
    body_file::MatrixEntries,
    reduction::{Eigensolver, Method},
};
use numpy::{IntoPyArray, PyArray1, PyArray2, ndarray::Array2};
use pyo3::prelude::*;

/// Raises `err` as the `flexmodes.errors` class of its layer, with `kind` (the variant's path,
/// e.g. `BodyFile.NotSymmetric`) and `data` (its fields) as attributes.
pub(crate) fn raise(py: Python<'_>, err: Error) -> PyErr {
    let class = match &err {
        Error::BodyFile(_) => "BodyFileError",
        Error::Linalg(_) => "LinalgError",
        Error::Reduction(_) => "ReductionError",
        Error::Dynamics(_) => "DynamicsError",
        Error::Mesh(_) => "InputError",
        Error::Mechanism { .. } => "MechanismError",
        Error::Cancelled => "Cancelled",
        Error::Io { .. } => "FileError",
        _ => "FlexmodesError",
    };
    let message = err.cause_chain();
    let (kind, data) = variant_path(serde_json::to_value(&err).unwrap_or_default());
    build_error(py, class, &message, &kind, &data.to_string())
}

/// The externally tagged variant names down to the fields: `{"BodyFile": {"NotSymmetric":
/// {...}}}` is `("BodyFile.NotSymmetric", {...})`.
pub(crate) fn variant_path(mut value: serde_json::Value) -> (String, serde_json::Value) {
    let mut path = Vec::new();
    loop {
        match value {
            serde_json::Value::String(s)
                if path.is_empty() || s.starts_with(char::is_uppercase) =>
            {
                path.push(s);
                return (path.join("."), serde_json::Value::Null);
            }
            serde_json::Value::Object(map)
                if map.len() == 1 && map.keys().all(|k| k.starts_with(char::is_uppercase)) =>
            {
                let (k, v) = map.into_iter().next().expect("one entry");
                path.push(k);
                value = v;
            }
            other => return (path.join("."), other),
        }
    }
}

pub(crate) fn build_error(
    py: Python<'_>,
    class: &str,
    message: &str,
    kind: &str,
    data: &str,
) -> PyErr {
    let made = (|| -> PyResult<PyErr> {
        let errors = py.import("flexmodes.errors")?;
        let value = errors.getattr(class)?.call1((message,))?;
        value.setattr("kind", kind)?;
        value.setattr("data", py.import("json")?.call_method1("loads", (data,))?)?;
        Ok(PyErr::from_value(value))
    })();
    made.unwrap_or_else(|e| e)
}

/// A bad argument: `flexmodes.errors.InputError` (also a `ValueError`).
pub(crate) fn input_error(py: Python<'_>, message: String) -> PyErr {
    build_error(py, "InputError", &message, "Input", "null")
}

/// Runs `work` with the GIL released. With a callback, a second thread calls
/// `callback(phase, fraction)` about every 0.2 s while the reading changes (`fraction`: of
/// the current time integration, or None); if the callback raises, the work is cancelled and
/// its exception re-raised. The watcher is woken when the work ends, so a call never waits
/// out its tick.
pub(crate) fn computing<T: Send>(
    py: Python<'_>,
    callback: Option<Py<PyAny>>,
    work: impl FnOnce(&Progress) -> flexmodes::Result<T> + Send,
) -> PyResult<T> {
    let progress = if callback.is_some() {
        Progress::new()
    } else {
        Progress::default()
    };
    let done = AtomicBool::new(false);
    let raised: Mutex<Option<PyErr>> = Mutex::new(None);
    let result = py.detach(|| {
        std::thread::scope(|scope| {
            let watcher = callback.as_ref().map(|callback| {
                let (progress, done, raised) = (&progress, &done, &raised);
                scope.spawn(move || {
                    let mut last = None;
                    while !done.load(Ordering::SeqCst) {
                        std::thread::park_timeout(Duration::from_millis(200));
                        let phase = progress.phase_reading().map(|p| p.name);
                        let fraction = progress
                            .reading()
                            .filter(|r| r.end_time > 0.0)
                            .map(|r| (r.time / r.end_time).clamp(0.0, 1.0));
                        let now = (phase.clone(), fraction.map(|f| (f * 1000.0) as i64));
                        if last.as_ref() == Some(&now) || done.load(Ordering::SeqCst) {
                            continue;
                        }
                        last = Some(now);
                        let failed =
                            Python::attach(|py| callback.call1(py, (phase, fraction)).err());
                        if let Some(e) = failed {
                            *raised.lock().expect("not poisoned") = Some(e);
                            progress.cancel();
                            break;
                        }
                    }
                })
            });
            let out = work(&progress);
            done.store(true, Ordering::SeqCst);
            if let Some(w) = &watcher {
                w.thread().unpark();
            }
            out
        })
    });
    if let Some(e) = raised.lock().expect("not poisoned").take() {
        return Err(e);
    }
    result.map_err(|e| raise(py, e))
}

pub(crate) fn matrix<'py>(py: Python<'py>, m: MatRef<'_, f64>) -> Bound<'py, PyArray2<f64>> {
    Array2::from_shape_fn((m.nrows(), m.ncols()), |(i, j)| m[(i, j)]).into_pyarray(py)
}

pub(crate) fn vector<'py>(py: Python<'py>, v: &[f64]) -> Bound<'py, PyArray1<f64>> {
    v.to_vec().into_pyarray(py)
}

pub(crate) fn json_to_py<'py>(
    py: Python<'py>,
    value: &serde_json::Value,
) -> PyResult<Bound<'py, PyAny>> {
    py.import("json")?
        .call_method1("loads", (value.to_string(),))
}

pub(crate) fn eigensolver(py: Python<'_>, id: &str) -> PyResult<Eigensolver> {
    Eigensolver::from_str(id).map_err(|e| input_error(py, e.to_string()))
}

pub(crate) fn method(py: Python<'_>, id: &str) -> PyResult<Method> {
    Method::from_str(id).map_err(|e| input_error(py, e.to_string()))
}

/// Entries from three NumPy arrays of equal length.
pub(crate) fn entries(
    py: Python<'_>,
    what: &str,
    (shape, rows, cols, values): crate::requests::Triplets<'_>,
) -> PyResult<MatrixEntries> {
    let (r, c, v) = (rows.as_slice()?, cols.as_slice()?, values.as_slice()?);
    if r.len() != v.len() || c.len() != v.len() {
        return Err(input_error(
            py,
            format!(
                "{what}: {} row indices, {} column indices and {} values",
                r.len(),
                c.len(),
                v.len()
            ),
        ));
    }
    if let Some(k) = r.iter().zip(c).position(|(&i, &j)| i < 0 || j < 0) {
        return Err(input_error(
            py,
            format!(
                "{what}: entry {k} has a negative index ({}, {})",
                r[k], c[k]
            ),
        ));
    }
    Ok(MatrixEntries {
        rows: shape.0,
        cols: shape.1,
        entries: r
            .iter()
            .zip(c)
            .zip(v)
            .map(|((&i, &j), &x)| (i as usize, j as usize, x))
            .collect(),
    })
}
