//! `kinegen` for Python: the engine's closed forms on NumPy arrays.
//!
//! A `Robot` holds what `kinegen eval` and `kinegen ik` work from (the chain and the
//! engine's derivation); every method evaluates the very nodes the generated Rust is
//! printed from (`Model::eval`) and solves IK through the runtime's solvers, by calling
//! the `kinegen_cli` library rather than restating it. Batches loop in Rust with the GIL
//! released. Bad input raises `ValueError`, a file that does not load `kinegen.LoadError`.

use std::sync::Arc;

mod tape;

use tape::{Layout, Tape};

use kinegen_cli::det_hook::{determinants, Determinants};
use kinegen_cli::{eval, formulas, ik, robots, CliError, UrdfArgs, What};
use kinegen_core::algebra::graph::Id;
use kinegen_core::front::toml_file::{load_description_file, load_description_str};
use kinegen_core::front::urdf::Urdf;
use kinegen_core::{derive, generate_from, Chain, Derived, ItemHeader, Options};
use numpy::ndarray::ArrayViewD;
use numpy::{
    AllowTypeChange, IntoPyArray, PyArrayDyn, PyArrayLikeDyn, PyArrayMethods, PyUntypedArrayMethods,
};
use pyo3::create_exception;
use pyo3::exceptions::{PyException, PyRuntimeError, PyValueError};
use pyo3::intern;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyTuple};

create_exception!(
    kinegen,
    LoadError,
    PyException,
    "A robot file did not load: one line per problem, `file:line: path: message`."
);

/// What a loaded robot keeps: the engine's input and results, derived once.
struct Inner {
    chain: Chain,
    derived: Derived,
    dets: Determinants,
    /// The nodes of fk's 3×4 rows, J's and J_ee's 6×N, row-major (for `_reference`).
    fk_ids: Vec<Id>,
    jacobian_ids: Vec<Id>,
    jacobian_ee_ids: Vec<Id>,
    /// The same outputs as tapes, and det J's and its factors' where it has them.
    fk: Tape,
    /// Every link's frame (`base · A1 ⋯ Ai`), 12 entries each.
    frames: Tape,
    jacobian: Tape,
    jacobian_ee: Tape,
    det: Option<Tape>,
    /// The square task Jacobian's determinant (planar and SCARA-like arms).
    task_det: Option<Tape>,
    factors: Option<Tape>,
    /// `FORMULAS` of the generated code, `(function, name, text, latex)`, made on first
    /// use (emitting the code's items takes as long as deriving them).
    formulas: std::sync::OnceLock<Vec<[String; 4]>>,
    /// The closed-form IK's solver, built once, or why the robot has none.
    solver: Result<ik::Solver, CliError>,
    /// The solver's registers, kept from call to call (one per call in flight: calls
    /// from several threads take one each).
    scratch: std::sync::Mutex<Vec<ik::Scratch>>,
}

/// A robot with its closed-form kinematics (see the module's docs).
#[pyclass(module = "kinegen", frozen)]
struct Robot {
    inner: Arc<Inner>,
}

fn to_py_err(e: CliError) -> PyErr {
    match e {
        CliError::Load(e) => LoadError::new_err(e.to_string()),
        CliError::Usage(m) => PyValueError::new_err(m),
    }
}

/// `f` with the GIL released for a batch (other Python threads run meanwhile); a single
/// item's call keeps it (its work takes microseconds).
fn released<T: Send>(py: Python<'_>, batch: bool, f: impl FnOnce() -> T + Send) -> T {
    if batch {
        py.allow_threads(f)
    } else {
        f()
    }
}

/// Run `f`, a panic inside the engine or the solvers becoming a `RuntimeError` (a bug to
/// report) rather than PyO3's `PanicException`, which is not an `Exception`.
fn guarded<T>(f: impl FnOnce() -> T) -> PyResult<T> {
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(f)).map_err(|e| {
        let why = e
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| e.downcast_ref::<String>().cloned())
            .unwrap_or_default();
        PyRuntimeError::new_err(format!("kinegen: internal error: {why}"))
    })
}

impl Robot {
    /// Derive `chain` (the GIL released: the engine takes milliseconds to seconds).
    fn build(py: Python<'_>, chain: Chain, options: Options) -> PyResult<Robot> {
        py.allow_threads(|| guarded(|| Robot::derive(chain, options)))
    }

    fn derive(chain: Chain, options: Options) -> Robot {
        let derived = derive(&chain, &options);
        let dets = determinants(&chain, &derived);
        let m = &derived.model;
        let fk_ids: Vec<Id> = m.fk_rows.iter().flatten().copied().collect();
        let jacobian_ids: Vec<Id> = m.jacobian.iter().flatten().copied().collect();
        let jacobian_ee_ids: Vec<Id> = m.jacobian_ee.iter().flatten().copied().collect();
        let factors = match &derived.det {
            Some(Ok(d)) => Some(Tape::new(
                m,
                &chain,
                &d.factors.iter().map(|f| f.node).collect::<Vec<_>>(),
            )),
            _ => None,
        };
        let solver = ik::Solver::new(&chain, &derived);
        Robot {
            inner: Arc::new(Inner {
                formulas: std::sync::OnceLock::new(),
                solver,
                scratch: std::sync::Mutex::new(Vec::new()),
                fk: Tape::new(m, &chain, &fk_ids),
                frames: Tape::new(
                    m,
                    &chain,
                    &m.frame_rows
                        .iter()
                        .flatten()
                        .flatten()
                        .copied()
                        .collect::<Vec<_>>(),
                ),
                jacobian: Tape::new(m, &chain, &jacobian_ids),
                jacobian_ee: Tape::new(m, &chain, &jacobian_ee_ids),
                det: dets.det.as_ref().map(|d| Tape::new(m, &chain, &[d.node])),
                task_det: dets
                    .det_task
                    .as_ref()
                    .map(|d| Tape::new(m, &chain, &[d.node])),
                factors,
                fk_ids,
                jacobian_ids,
                jacobian_ee_ids,
                chain,
                derived,
                dets,
            }),
        }
    }

    fn dof(&self) -> usize {
        self.inner.chain.dof()
    }
}

impl Inner {
    /// The IK solver, or why the robot has none.
    fn solver(&self) -> Result<&ik::Solver, CliError> {
        self.solver.as_ref().map_err(Clone::clone)
    }

    /// `f` with the solver and registers of it that no other call is using (made on
    /// first use, then reused: a single pose's solve is short next to making them).
    fn solving<T>(
        &self,
        f: impl FnOnce(&ik::Solver, &std::cell::RefCell<ik::Scratch>) -> Result<T, CliError>,
    ) -> Result<T, CliError> {
        let solver = self.solver()?;
        let pool = || self.scratch.lock().unwrap_or_else(|e| e.into_inner());
        let taken = pool().pop();
        let scratch = std::cell::RefCell::new(taken.unwrap_or_else(|| solver.scratch()));
        let result = f(solver, &scratch);
        pool().push(scratch.into_inner());
        result
    }
}

/// Joint vectors read from a 1-D array of N or an (M, N) batch: the rows, flat, and
/// whether it was a batch. Wrong shapes and non-finite values are `ValueError`s.
struct Batch {
    data: Vec<f64>,
    rows: usize,
    batch: bool,
}

/// Read `x` as one item of shape `item` or a batch of them (`(M, *item)`): a
/// C-contiguous float64 array (what NumPy makes by default) copied in one step, anything
/// else NumPy can turn into float64 (lists, other dtypes, other layouts) converted first.
fn read_batch(x: &Bound<'_, PyAny>, item: &[usize], what: &str) -> PyResult<Batch> {
    // The array's memory read directly (the GIL held while it is copied): without the
    // conversion and the borrow bookkeeping of a `PyArrayLike` (about 1 200 of the 6 100
    // instructions of a single UR5 `jacobian` call, callgrind).
    if let Ok(a) = x.downcast::<PyArrayDyn<f64>>() {
        if a.is_c_contiguous() {
            if let Ok(data) = a.to_vec() {
                return checked_batch(a.shape(), data, item, what);
            }
        }
    }
    let like: PyArrayLikeDyn<'_, f64, AllowTypeChange> = x.extract()?;
    let view: ArrayViewD<'_, f64> = like.as_array();
    let data: Vec<f64> = view.iter().copied().collect();
    checked_batch(view.shape(), data, item, what)
}

/// `data` (row-major, of `shape`) as one item of shape `item` or a batch of them; wrong
/// shapes and non-finite values are `ValueError`s.
fn checked_batch(shape: &[usize], data: Vec<f64>, item: &[usize], what: &str) -> PyResult<Batch> {
    let batch = if shape == item {
        false
    } else if shape.len() == item.len() + 1 && &shape[1..] == item {
        true
    } else {
        let want = item
            .iter()
            .map(|d| d.to_string())
            .collect::<Vec<_>>()
            .join(", ");
        return Err(PyValueError::new_err(format!(
            "{what}: expected shape ({want}) or (M, {want}), got {shape:?}"
        )));
    };
    let rows = if batch { shape[0] } else { 1 };
    if let Some(i) = data.iter().position(|v| !v.is_finite()) {
        let per: usize = item.iter().product::<usize>().max(1);
        let at = if batch {
            format!(" (row {})", i / per)
        } else {
            String::new()
        };
        return Err(PyValueError::new_err(format!(
            "{what}: entry {} is not a finite number{at}",
            i % per
        )));
    }
    Ok(Batch { data, rows, batch })
}

/// An array of `shape` (with a leading M for a batch) from flat values.
fn to_array<'py>(
    py: Python<'py>,
    values: Vec<f64>,
    batch: Option<usize>,
    shape: &[usize],
) -> PyResult<Bound<'py, PyAny>> {
    let mut full: Vec<usize> = batch.into_iter().collect();
    full.extend_from_slice(shape);
    if full.is_empty() {
        return Ok(values[0].into_pyobject(py)?.into_any());
    }
    shaped(py, values, full)
}

/// An array of `shape` from flat row-major values, made in one step (numpy's reshape
/// of a flat array is a second call that costs as much as the first).
fn shaped<'py, T: numpy::Element>(
    py: Python<'py>,
    values: Vec<T>,
    shape: Vec<usize>,
) -> PyResult<Bound<'py, PyAny>> {
    let a = numpy::ndarray::ArrayD::from_shape_vec(shape, values)
        .map_err(|e| PyRuntimeError::new_err(format!("kinegen: internal error: {e}")))?;
    Ok(a.into_pyarray(py).into_any())
}

impl Robot {
    /// Evaluate `f` (which writes `len` values from one joint vector) on every row of `q`,
    /// the GIL released for a batch; the result has shape `shape`, `(M, *shape)` for a
    /// batch.
    fn map_q<'py, F>(
        &self,
        py: Python<'py>,
        q: Bound<'py, PyAny>,
        shape: &[usize],
        f: F,
    ) -> PyResult<Bound<'py, PyAny>>
    where
        F: Fn(&Inner, &[f64], &mut Vec<f64>, &mut Vec<f64>) + Send + Sync,
    {
        let n = self.dof();
        let b = read_batch(&q, &[n], "q")?;
        let inner = &*self.inner;
        let out = released(py, b.batch, || {
            guarded(|| {
                let size: usize = shape.iter().product();
                let mut out = Vec::with_capacity(size * b.rows);
                let mut regs = Vec::new();
                for row in b.data.chunks(n.max(1)).take(b.rows) {
                    f(inner, row, &mut regs, &mut out);
                }
                out
            })
        })?;
        to_array(py, out, b.batch.then_some(b.rows), shape)
    }

    /// Evaluate `tape(inner)` on every row of `q` (four rows side by side, the GIL
    /// released for a batch), each row's outputs laid out by `layout` (`None`: as they
    /// are); the result has shape `shape`, `(M, *shape)` for a batch.
    fn map_tape<'py>(
        &self,
        py: Python<'py>,
        q: Bound<'py, PyAny>,
        shape: &[usize],
        tape: fn(&Inner) -> Option<&Tape>,
        layout: Option<Layout>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let n = self.dof();
        let b = read_batch(&q, &[n], "q")?;
        let inner = &*self.inner;
        let out = released(py, b.batch, || {
            guarded(|| {
                let Some(t) = tape(inner) else {
                    return Vec::new();
                };
                let mut out = Vec::with_capacity(shape.iter().product::<usize>() * b.rows);
                t.eval_rows(&b.data, n, b.rows, layout, &mut out);
                out
            })
        })?;
        to_array(py, out, b.batch.then_some(b.rows), shape)
    }

    fn det_or_err(&self) -> PyResult<()> {
        match self.inner.dets.det {
            Some(_) => Ok(()),
            None => Err(PyValueError::new_err(format!(
                "`{}`: det J {}",
                self.inner.chain.name, self.inner.dets.missing
            ))),
        }
    }
}

fn manipulability(inner: &Inner, q: &[f64], regs: &mut Vec<f64>) -> f64 {
    let n = inner.chain.dof();
    let mut j = Vec::with_capacity(6 * n);
    inner.jacobian.eval(q, regs, &mut j);
    let m = nalgebra::DMatrix::from_row_slice(6, n, &j);
    kinegen_core::numeric::manipulability(&m)
}

#[pymethods]
impl Robot {
    /// A chain of a URDF file: from `base` (default: the root link) to `tip` (default:
    /// the only leaf after a moving joint, or the one before a parallel gripper's
    /// fingers); angles within `snap` rad of a multiple of pi/12 and lengths within
    /// `snap` m of 0 are taken exact (0 keeps every decimal); `symbolic` names every
    /// length;
    /// `task` the rows an arm with fewer than six joints solves (`["x", "y", "z", "rz"]`
    /// for a SCARA).
    #[staticmethod]
    #[pyo3(signature = (path, base=None, tip=None, snap=1e-4, symbolic=false, task=None))]
    fn from_urdf(
        py: Python<'_>,
        path: std::path::PathBuf,
        base: Option<String>,
        tip: Option<String>,
        snap: f64,
        symbolic: bool,
        task: Option<Vec<String>>,
    ) -> PyResult<Robot> {
        if !snap.is_finite() || snap < 0.0 {
            return Err(PyValueError::new_err(format!(
                "snap: expected a finite number >= 0, got {snap}"
            )));
        }
        let urdf = Urdf::load_file(&path).map_err(|e| LoadError::new_err(e.to_string()))?;
        let args = UrdfArgs {
            base,
            tip,
            snap: Some(snap),
            symbolic,
            task,
        };
        let chain = robots::urdf_chain(&urdf, &args).map_err(to_py_err)?;
        Robot::build(py, chain, Options::default())
    }

    /// A robot file in kinegen's TOML format (a DH table, or a file naming a URDF).
    #[staticmethod]
    fn from_toml(py: Python<'_>, path: std::path::PathBuf) -> PyResult<Robot> {
        let (d, options) =
            load_description_file(&path).map_err(|e| LoadError::new_err(e.to_string()))?;
        Robot::build(py, d.chain(), options)
    }

    /// A DH table: `rows` is a list of dicts with the TOML file's columns (`a`, `alpha`,
    /// `d`, `theta`, `offset`, `limits`, `flip`, and `type` = "revolute" (default) or
    /// "prismatic"), or of tuples `(a, alpha, d)` / `(a, alpha, d, offset)` of revolute
    /// joints. Values are numbers or expressions (`"pi/2"`, a name of `params`).
    #[staticmethod]
    #[pyo3(signature = (rows, convention="standard", params=None, name="DH robot"))]
    fn from_dh(
        py: Python<'_>,
        rows: &Bound<'_, PyAny>,
        convention: &str,
        params: Option<&Bound<'_, PyDict>>,
        name: &str,
    ) -> PyResult<Robot> {
        let src = dh_toml(rows, convention, params, name)?;
        let no_urdf = |rel: &str| Err(format!("`{rel}`: from_dh reads no URDF"));
        let (d, options) = load_description_str(&src, "<from_dh>", &no_urdf)
            .map_err(|e| LoadError::new_err(e.to_string()))?;
        Robot::build(py, d.chain(), options)
    }

    /// Load a robot shipped with kinegen by name (`"ur5"`); see `kinegen.robots`.
    #[staticmethod]
    fn shipped(py: Python<'_>, name: &str) -> PyResult<Robot> {
        if name.contains(['/', '\\', '.']) || std::path::Path::new(name).is_file() {
            return Err(PyValueError::new_err(format!(
                "`{name}` is a path: use Robot.from_toml or Robot.from_urdf"
            )));
        }
        let (chain, options) = robots::load(name, &UrdfArgs::default()).map_err(to_py_err)?;
        Robot::build(py, chain, options)
    }

    /// The robot's name.
    #[getter]
    fn name(&self) -> String {
        self.inner.chain.name.clone()
    }

    /// Number of joints.
    #[getter(dof)]
    fn py_dof(&self) -> usize {
        self.dof()
    }

    /// Joint names, base to tip.
    #[getter]
    fn joint_names(&self) -> Vec<String> {
        self.inner
            .chain
            .links
            .iter()
            .map(|l| l.name.clone())
            .collect()
    }

    /// Joint limits, an (N, 2) array of `[min, max]` (±inf where the robot has none).
    #[getter]
    fn limits<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let v: Vec<f64> = self
            .inner
            .chain
            .links
            .iter()
            .flat_map(|l| l.limits.unwrap_or([f64::NEG_INFINITY, f64::INFINITY]))
            .collect();
        to_array(py, v, None, &[self.dof(), 2])
    }

    /// Whether the robot has a closed-form det J (a square 6×6 Jacobian).
    #[getter]
    fn has_det(&self) -> bool {
        self.inner.dets.det.is_some()
    }

    /// The factors of det J (or, for a robot with square task rows, of the task
    /// Jacobian's det) as `(text, power, joints)` (joints 1-based): the determinant is a
    /// constant times the product of `factor ** power`. Empty without a closed form.
    #[getter]
    fn det_factors(&self) -> Vec<(String, u32, Vec<usize>)> {
        match &self.inner.derived.det {
            Some(Ok(d)) => d
                .factors
                .iter()
                .map(|f| (f.text.clone(), f.power, f.joints.clone()))
                .collect(),
            _ => Vec::new(),
        }
    }

    /// Tool pose: (4, 4), or (M, 4, 4) for an (M, N) batch of joint vectors.
    fn fk<'py>(&self, py: Python<'py>, q: Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
        self.map_tape(py, q, &[4, 4], |i| Some(&i.fk), Some(with_bottom_rows))
    }

    /// Every link's frame in the world frame (`base · A1 ⋯ Ai`, without the tool), as
    /// the generated `frames`: (N, 4, 4), or (M, N, 4, 4) for a batch.
    fn frames<'py>(&self, py: Python<'py>, q: Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
        let n = self.dof();
        self.map_tape(
            py,
            q,
            &[n, 4, 4],
            |i| Some(&i.frames),
            Some(with_bottom_rows),
        )
    }

    /// Geometric Jacobian in the world frame, rows `[vx vy vz wx wy wz]`: (6, N) or (M, 6, N).
    fn jacobian<'py>(&self, py: Python<'py>, q: Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
        self.map_tape(py, q, &[6, self.dof()], |i| Some(&i.jacobian), None)
    }

    /// Geometric Jacobian in the tool frame: (6, N) or (M, 6, N).
    fn jacobian_ee<'py>(
        &self,
        py: Python<'py>,
        q: Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.map_tape(py, q, &[6, self.dof()], |i| Some(&i.jacobian_ee), None)
    }

    /// det J from its closed form: a float, or an (M,) array. `ValueError` for a robot
    /// without one (see `has_det`).
    fn jacobian_det<'py>(
        &self,
        py: Python<'py>,
        q: Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.det_or_err()?;
        self.map_tape(py, q, &[], |i| i.det.as_ref(), None)
    }

    /// The determinant of the square task Jacobian (the rows the arm controls, e.g.
    /// `[x, y, rz]` of a planar arm) from its closed form: a float, or an (M,) array.
    /// `ValueError` for a robot without a square task (see `jacobian_det`).
    fn task_jacobian_det<'py>(
        &self,
        py: Python<'py>,
        q: Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyAny>> {
        if self.inner.task_det.is_none() {
            return Err(PyValueError::new_err(format!(
                "`{}`: no square task Jacobian with a closed-form determinant",
                self.inner.chain.name
            )));
        }
        self.map_tape(py, q, &[], |i| i.task_det.as_ref(), None)
    }

    /// The factors of `det_factors` at `q`: `(names, values)`, values (K,) or (M, K). The
    /// Jacobian (or the square task Jacobian) is singular where one of them is zero.
    /// `ValueError` for a robot without a closed-form determinant.
    fn singular_factors<'py>(
        &self,
        py: Python<'py>,
        q: Bound<'py, PyAny>,
    ) -> PyResult<(Vec<String>, Bound<'py, PyAny>)> {
        let Some(Ok(det)) = &self.inner.derived.det else {
            return Err(PyValueError::new_err(format!(
                "`{}`: no closed-form determinant: {}",
                self.inner.chain.name, self.inner.dets.missing
            )));
        };
        let names: Vec<String> = det.factors.iter().map(|f| f.text.clone()).collect();
        let values = self.map_tape(py, q, &[names.len()], |i| i.factors.as_ref(), None)?;
        Ok((names, values))
    }

    /// Yoshikawa's manipulability `sqrt(det(J J^T))` of the 6×N world Jacobian (0 for
    /// N < 6): a float or an (M,) array.
    fn manipulability<'py>(
        &self,
        py: Python<'py>,
        q: Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.map_q(py, q, &[], |inner, q, regs, out| {
            out.push(manipulability(inner, q, regs))
        })
    }

    /// `H[k] = dJ/dq_k` of the world Jacobian: (N, 6, N) or (M, N, 6, N).
    fn hessian<'py>(&self, py: Python<'py>, q: Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
        let n = self.dof();
        self.map_q(py, q, &[n, 6, n], |inner, q, _, out| {
            let v = eval::values(&inner.chain, &inner.derived, &inner.dets, q, None);
            out.extend(v.second.hessian.iter().flatten().flatten());
        })
    }

    /// `dJ/dt qd` (the acceleration term of `xdd = J qdd + Jdot qd`): (6,) or (M, 6);
    /// `q` and `qd` of the same shape.
    fn jdot_qdot<'py>(
        &self,
        py: Python<'py>,
        q: Bound<'py, PyAny>,
        qd: Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let n = self.dof();
        let b = read_batch(&q, &[n], "q")?;
        let r = read_batch(&qd, &[n], "qd")?;
        if (b.rows, b.batch) != (r.rows, r.batch) {
            return Err(PyValueError::new_err(
                "qd: expected the shape of q (one joint rate per joint value)",
            ));
        }
        let inner = &*self.inner;
        let out = released(py, b.batch, || {
            guarded(|| {
                let mut out = Vec::with_capacity(6 * b.rows);
                for (q, qd) in b.data.chunks(n).zip(r.data.chunks(n)) {
                    let v = eval::values(&inner.chain, &inner.derived, &inner.dets, q, Some(qd));
                    out.extend(v.second.jdot_qdot.unwrap_or_default());
                }
                out
            })
        })?;
        to_array(py, out, b.batch.then_some(b.rows), &[6])
    }

    /// Every closed-form IK solution of `pose` (4×4) or of each pose of an (M, 4, 4)
    /// batch; `locked` is the locked joint's value of a 7-joint arm. Returns a dict:
    /// `q` (K, N) (a batch: (M, K, N), padded with NaN), `valid` (mask of real entries),
    /// `exact` (solves the pose; else the least-squares nearest), `singular` (as the
    /// generated `ik` flags a branch: a subproblem met a singular configuration, the
    /// vanishing factors of det J measured there), `within_limits`, `residual`
    /// (max |fk(q) - pose|), and for one pose `singular_factors` (names of the vanishing
    /// factors of each solution).
    /// `residuals=False` leaves the residual out (NaN): measuring it evaluates fk once
    /// per solution, which costs more than the solving.
    #[pyo3(signature = (pose, locked=None, residuals=true))]
    fn ik<'py>(
        &self,
        py: Python<'py>,
        pose: Bound<'py, PyAny>,
        locked: Option<f64>,
        residuals: bool,
    ) -> PyResult<Bound<'py, PyDict>> {
        let poses = read_poses(&pose)?;
        let inner = &*self.inner;
        let solved = released(py, poses.batch, || {
            guarded(|| {
                inner.solving(|solver, scratch| {
                    Solved::new(solver, scratch, &poses.poses, locked, residuals)
                })
            })
        })?;
        let solved = solved.map_err(to_py_err)?;
        ik_dict(py, solved, poses.batch)
    }

    /// The exact IK solution nearest to the configuration `q` (whole turns of revolute
    /// joints chosen nearest to it within the limits), as the generated `ik_near`: an
    /// array of N, or None when the pose is out of reach. A batch of (M, 4, 4) poses and
    /// (M, N) configurations gives `(q (M, N) with NaN rows, found (M,) mask)`.
    fn ik_near<'py>(
        &self,
        py: Python<'py>,
        pose: Bound<'py, PyAny>,
        q: Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let n = self.dof();
        let poses = read_poses(&pose)?;
        let near = read_batch(&q, &[n], "q")?;
        if (near.rows, near.batch) != (poses.poses.len(), poses.batch) {
            return Err(PyValueError::new_err(
                "q: expected one configuration per pose ((N,) with a 4×4 pose, (M, N) with (M, 4, 4))",
            ));
        }
        let inner = &*self.inner;
        let found = released(py, poses.batch, || {
            guarded(|| {
                inner.solving(|solver, scratch| {
                    let mut sols = kinegen::ik::dispatch::DynSolutions::default();
                    poses
                        .poses
                        .iter()
                        .zip(near.data.chunks(n))
                        .map(|(p, q)| solver.near_into(*p, q, scratch, &mut sols))
                        .collect::<Result<Vec<_>, _>>()
                })
            })
        })?;
        let found = found.map_err(to_py_err)?;
        if !poses.batch {
            return match &found[0] {
                Some(q) => to_array(py, q.clone(), None, &[n]),
                None => Ok(py.None().into_bound(py)),
            };
        }
        let mask: Vec<bool> = found.iter().map(Option::is_some).collect();
        let values: Vec<f64> = found
            .into_iter()
            .flat_map(|q| q.unwrap_or_else(|| vec![f64::NAN; n]))
            .collect();
        let q = to_array(py, values, Some(mask.len()), &[n])?;
        let mask = mask.into_pyarray(py).into_any();
        Ok(PyTuple::new(py, [q, mask])?.into_any())
    }

    /// fk, J or J_ee (`which`) at one configuration evaluated by walking the engine's
    /// graph (`Model::eval`, as `kinegen eval`), flat: what the tests compare the
    /// instruction lists of the other methods with.
    fn _reference<'py>(
        &self,
        py: Python<'py>,
        which: &str,
        q: Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let i = &self.inner;
        let ids = match which {
            "fk" => &i.fk_ids,
            "jacobian" => &i.jacobian_ids,
            "jacobian_ee" => &i.jacobian_ee_ids,
            _ => return Err(PyValueError::new_err(format!("which: `{which}`"))),
        };
        let b = read_batch(&q, &[self.dof()], "q")?;
        let v = i.derived.model.eval(&i.chain, &b.data, ids);
        to_array(py, v, None, &[ids.len()])
    }

    /// The IK family the engine chose, or None without a closed-form IK.
    #[getter]
    fn ik_family(&self) -> Option<String> {
        // The derived IK model's name (what `Solver::family` returns), without building
        // a solver and its programs for it.
        let ik = self.inner.derived.ik.as_ref().ok()?;
        Some(ik.plan.name.clone())
    }

    /// Every closed form of the generated code, as its `FORMULAS` lists them: dicts of
    /// `function` (`"fk"`, `"jacobian"`, `"jacobian_det"`, `"hessian"`, …), `name`
    /// (`"t4"`, `"c23"` for a shared intermediate, `"T[0][3]"`, `"J[2][1]"`, `"det"`),
    /// `text` (Rust syntax) and `latex`, each function's intermediates before its outputs;
    /// at most the first 10 000, as `FORMULAS` (a chain of hundreds of joints has more).
    #[getter]
    fn formulas<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let i = &*self.inner;
        let entries = py.allow_threads(|| {
            guarded(|| {
                i.formulas
                    .get_or_init(|| {
                        let d = &i.derived;
                        kinegen_core::emit::functions::functions(
                            &i.chain,
                            &d.model,
                            &d.det,
                            &d.second,
                            &d.det_gradient,
                            &d.ik,
                        )
                        .formulas
                        .entries()
                        .map(|(f, n, t, l)| [f, n, t, l].map(String::from))
                        .collect()
                    })
                    .clone()
            })
        })?;
        let list = PyList::empty(py);
        for [function, name, text, latex] in entries {
            let d = PyDict::new(py);
            d.set_item("function", function)?;
            d.set_item("name", name)?;
            d.set_item("text", text)?;
            d.set_item("latex", latex)?;
            list.append(d)?;
        }
        Ok(list)
    }

    /// det J as `kinegen show --what det` prints it (the factored closed form).
    #[getter]
    fn det(&self) -> String {
        self.show(What::Det, false)
    }

    /// The closed forms as a LaTeX document body (amsmath `align*`), as
    /// `kinegen show --latex` prints it; `what` is one of "fk", "jacobian", "det",
    /// "singularities", "all".
    #[pyo3(signature = (what="all"))]
    fn latex(&self, what: &str) -> PyResult<String> {
        let w = match what {
            "fk" => What::Fk,
            "jacobian" => What::Jacobian,
            "det" => What::Det,
            "singularities" => What::Singularities,
            "all" => What::All,
            _ => {
                return Err(PyValueError::new_err(format!(
                    "what: expected fk, jacobian, det, singularities or all, got `{what}`"
                )))
            }
        };
        Ok(self.show(w, true))
    }

    /// The Rust code `kinematics!` generates for the robot, as `kinegen rust` prints it
    /// (from the derivation the robot holds).
    fn rust(&self) -> String {
        let i = &self.inner;
        generate_from(&i.chain, &ItemHeader::public(&i.chain.name), &i.derived).pretty()
    }

    /// det J in LaTeX for Jupyter (the robot's name where it has none).
    fn _repr_latex_(&self) -> String {
        match &self.inner.dets.det {
            Some(d) => format!("$\\det J = {}$", d.latex),
            None => format!("$\\text{{{}}}$", self.inner.chain.name),
        }
    }

    /// The robot, det J and its singular factors for Jupyter: the `kinegen report`
    /// page's MathML and plain text (the same printer), in one `<div>`.
    fn _repr_html_(&self) -> String {
        use kinegen_cli::report::{formulas as page, html};
        use kinegen_core::emit::mathml;
        let i = &self.inner;
        let family = i
            .derived
            .ik
            .as_ref()
            .map_or("none".to_string(), |m| m.plan.name.clone());
        let mut s = String::from("<div class=\"kinegen\">\n");
        s.push_str(&html::p(&format!(
            "{}: {} joints; closed-form IK: {family}",
            i.chain.name,
            i.chain.dof()
        )));
        let det = (i.dets.det.as_ref().map(|d| ("det J", d)))
            .or_else(|| i.dets.det_task.as_ref().map(|d| ("det Jt", d)));
        if let Some((name, d)) = det {
            let rhs = mathml::to_mathml(&d.text).unwrap_or_else(|_| mathml::mtext(&d.text));
            let eq = mathml::math(&mathml::equation(&page::lhs(name), &[rhs]), true);
            s.push_str(&html::equation(&eq, &format!("{name} = {}", d.text)));
        }
        s.push_str(&page::singular_factors(&i.dets).body);
        s.push_str("</div>\n");
        s
    }

    fn __repr__(&self) -> String {
        format!(
            "<kinegen.Robot {:?}: {} joints>",
            self.inner.chain.name,
            self.dof()
        )
    }
}

impl Robot {
    fn show(&self, what: What, latex: bool) -> String {
        let i = &self.inner;
        formulas::show(&i.chain, &i.derived.model, &i.dets, what, latex)
    }
}

/// Poses read from a (4, 4) array or an (M, 4, 4) batch, each checked as the CLI checks
/// `--pose` (finite, last row 0 0 0 1, a rotation).
struct Poses {
    poses: Vec<[[f64; 4]; 4]>,
    batch: bool,
}

fn read_poses(x: &Bound<'_, PyAny>) -> PyResult<Poses> {
    let b = read_batch(x, &[4, 4], "pose")?;
    let poses = b
        .data
        .chunks(16)
        .enumerate()
        .map(|(i, p)| {
            // The batch index is written into the message of a pose that fails only: no
            // string is made for the others.
            ik::pose_from(p, "pose").map_err(|e| match e {
                CliError::Usage(m) if b.batch => {
                    to_py_err(CliError::Usage(m.replacen("pose", &format!("pose {i}"), 1)))
                }
                e => to_py_err(e),
            })
        })
        .collect::<PyResult<Vec<_>>>()?;
    Ok(Poses {
        poses,
        batch: b.batch,
    })
}

/// A tape's 12 entries of each frame (3×4, row-major), each followed by its bottom row.
fn with_bottom_rows(rows: &[f64], out: &mut Vec<f64>) {
    for frame in rows.chunks(12) {
        out.extend_from_slice(frame);
        out.extend([0.0, 0.0, 0.0, 1.0]);
    }
}

/// The solutions of a batch of poses as `Robot.ik` returns them: `k` places per pose
/// (the most solutions any pose has), the unused ones padded (NaN, `false`), written in
/// place pose after pose — no allocation per pose, no copy into the arrays at the end.
struct Solved {
    /// Poses, and joints per solution.
    m: usize,
    n: usize,
    /// Places per pose; when a pose has more solutions, every pose's rows are spread out
    /// to the new count (at most a few times a batch: a robot has at most 16 solutions).
    k: usize,
    /// `(M, k, n)` joint values.
    q: Vec<f64>,
    /// `(M, k)` masks and residuals.
    valid: Vec<bool>,
    exact: Vec<bool>,
    /// A factor of det J vanishes, or a subproblem met a singular configuration.
    singular: Vec<bool>,
    within_limits: Vec<bool>,
    residual: Vec<f64>,
    /// The vanishing factors' names of each solution of the first pose.
    first_names: Vec<Vec<String>>,
}

impl Solved {
    fn new(
        solver: &ik::Solver,
        scratch: &std::cell::RefCell<ik::Scratch>,
        poses: &[[[f64; 4]; 4]],
        locked: Option<f64>,
        residuals: bool,
    ) -> Result<Solved, CliError> {
        let n = solver.chain().dof();
        let mut out = Solved {
            m: poses.len(),
            n,
            k: 0,
            q: Vec::new(),
            valid: Vec::new(),
            exact: Vec::new(),
            singular: Vec::new(),
            within_limits: Vec::new(),
            residual: Vec::new(),
            first_names: Vec::new(),
        };
        let mut sols = kinegen::ik::dispatch::DynSolutions::default();
        let mut misses = Vec::new();
        for (i, p) in poses.iter().enumerate() {
            solver.measured_into(
                *p,
                None,
                locked,
                None,
                residuals,
                scratch,
                &mut sols,
                &mut misses,
            )?;
            if sols.len() > out.k {
                out.spread(i, sols.len());
                if i == 0 {
                    // The first pose's own count: reserve for the batch at once (growing
                    // as it goes instead cost 1 247 instructions per pose of gathering
                    // against 870, callgrind, UR5, 10 000 poses).
                    out.reserve(poses.len());
                }
            }
            for (j, miss) in misses.iter().enumerate() {
                let f = sols.flags(j);
                out.q.extend_from_slice(sols.q(j));
                out.valid.push(true);
                out.exact.push(f.exact);
                out.singular.push(f.at_singularity || f.singular != 0);
                out.within_limits.push(f.within_limits);
                out.residual.push(*miss);
                if i == 0 {
                    out.first_names.push(solver.names(f.singular));
                }
            }
            out.pad(out.k - sols.len());
        }
        Ok(out)
    }

    /// The four masks, one entry per place.
    fn masks(&mut self) -> [&mut Vec<bool>; 4] {
        [
            &mut self.valid,
            &mut self.exact,
            &mut self.singular,
            &mut self.within_limits,
        ]
    }

    /// Room for `m` poses of `k` places.
    fn reserve(&mut self, m: usize) {
        let places = m * self.k;
        self.q.reserve(places * self.n);
        self.residual.reserve(places);
        for v in self.masks() {
            v.reserve(places);
        }
    }

    /// `count` unused places.
    fn pad(&mut self, count: usize) {
        self.q.resize(self.q.len() + count * self.n, f64::NAN);
        self.residual.resize(self.residual.len() + count, f64::NAN);
        for v in self.masks() {
            v.resize(v.len() + count, false);
        }
    }

    /// The `m` poses written so far re-laid with `k` places each (`k` > `self.k`).
    fn spread(&mut self, m: usize, k: usize) {
        fn respace<T: Copy>(v: &mut Vec<T>, m: usize, from: usize, to: usize, fill: T) {
            let mut w = Vec::with_capacity(m * to);
            for row in v.chunks(from.max(1)).take(m) {
                w.extend_from_slice(row);
                w.resize(w.len() + to - from, fill);
            }
            if from == 0 {
                w.resize(m * to, fill);
            }
            *v = w;
        }
        let (n, old) = (self.n, self.k);
        respace(&mut self.q, m, old * n, k * n, f64::NAN);
        respace(&mut self.residual, m, old, k, f64::NAN);
        for v in self.masks() {
            respace(v, m, old, k, false);
        }
        self.k = k;
    }
}

/// The dict `Robot.ik` returns: `solved`'s arrays moved into NumPy's.
fn ik_dict(py: Python<'_>, solved: Solved, batch: bool) -> PyResult<Bound<'_, PyDict>> {
    let (m, n, k) = (solved.m, solved.n, solved.k);
    let lead: Vec<usize> = if batch { vec![m, k] } else { vec![k] };
    let mask = |v: Vec<bool>| shaped(py, v, lead.clone());
    let d = PyDict::new(py);
    let mut q_shape = lead.clone();
    q_shape.push(n);
    // The keys made once per interpreter, not per call.
    d.set_item(intern!(py, "q"), shaped(py, solved.q, q_shape)?)?;
    d.set_item(intern!(py, "valid"), mask(solved.valid)?)?;
    d.set_item(intern!(py, "exact"), mask(solved.exact)?)?;
    d.set_item(intern!(py, "singular"), mask(solved.singular)?)?;
    d.set_item(intern!(py, "within_limits"), mask(solved.within_limits)?)?;
    d.set_item(
        intern!(py, "residual"),
        shaped(py, solved.residual, lead.clone())?,
    )?;
    if !batch {
        let names = PyList::new(py, &solved.first_names)?;
        d.set_item(intern!(py, "singular_factors"), names)?;
    }
    Ok(d)
}

/// The TOML text of a DH table given to `Robot.from_dh`.
fn dh_toml(
    rows: &Bound<'_, PyAny>,
    convention: &str,
    params: Option<&Bound<'_, PyDict>>,
    name: &str,
) -> PyResult<String> {
    use toml::{Table, Value};
    let value = |x: &Bound<'_, PyAny>, what: &str| -> PyResult<Value> {
        if let Ok(b) = x.extract::<bool>() {
            return Ok(Value::Boolean(b));
        }
        if let Ok(s) = x.extract::<String>() {
            return Ok(Value::String(s));
        }
        if let Ok(v) = x.extract::<f64>() {
            if !v.is_finite() {
                return Err(PyValueError::new_err(format!(
                    "{what}: {v} is not a finite number"
                )));
            }
            return Ok(Value::Float(v));
        }
        if let Ok(l) = x.extract::<Vec<Bound<'_, PyAny>>>() {
            let items = l
                .iter()
                .map(|i| match i.extract::<String>() {
                    Ok(s) => Ok(Value::String(s)),
                    Err(_) => i.extract::<f64>().map(Value::Float).map_err(|_| {
                        PyValueError::new_err(format!("{what}: expected numbers or strings"))
                    }),
                })
                .collect::<PyResult<Vec<_>>>()?;
            return Ok(Value::Array(items));
        }
        Err(PyValueError::new_err(format!(
            "{what}: expected a number, a string or a list, got {}",
            x.get_type().name()?
        )))
    };
    let mut top = Table::new();
    top.insert("name".into(), Value::String(name.into()));
    top.insert("convention".into(), Value::String(convention.into()));
    if let Some(p) = params {
        let mut t = Table::new();
        for (k, v) in p.iter() {
            let k: String = k.extract()?;
            let what = format!("params[{k:?}]");
            t.insert(k, value(&v, &what)?);
        }
        top.insert("params".into(), Value::Table(t));
    }
    let mut joints = Vec::new();
    for (i, row) in rows.try_iter()?.enumerate() {
        let row = row?;
        let mut t = Table::new();
        if let Ok(d) = row.downcast::<PyDict>() {
            t.insert("type".into(), Value::String("revolute".into()));
            for (k, v) in d.iter() {
                let k: String = k.extract()?;
                let what = format!("rows[{i}][{k:?}]");
                t.insert(k, value(&v, &what)?);
            }
        } else {
            let cells: Vec<Bound<'_, PyAny>> = row.extract().map_err(|_| {
                PyValueError::new_err(format!(
                    "rows[{i}]: expected a dict of columns or a tuple (a, alpha, d[, offset])"
                ))
            })?;
            if !(3..=4).contains(&cells.len()) {
                return Err(PyValueError::new_err(format!(
                    "rows[{i}]: a tuple row is (a, alpha, d) or (a, alpha, d, offset), got {} values",
                    cells.len()
                )));
            }
            t.insert("type".into(), Value::String("revolute".into()));
            for (c, key) in cells.iter().zip(["a", "alpha", "d", "offset"]) {
                t.insert(key.into(), value(c, &format!("rows[{i}].{key}"))?);
            }
        }
        joints.push(Value::Table(t));
    }
    top.insert("joints".into(), Value::Array(joints));
    toml::to_string(&top).map_err(|e| PyValueError::new_err(e.to_string()))
}

/// Names of the robots shipped with kinegen (`kinegen.robots`).
#[pyfunction]
fn robot_names() -> Vec<&'static str> {
    robots::names().collect()
}

/// The native part of the `kinegen` package.
#[pymodule]
fn _kinegen(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Robot>()?;
    m.add("LoadError", m.py().get_type::<LoadError>())?;
    m.add_function(wrap_pyfunction!(robot_names, m)?)?;
    Ok(())
}
