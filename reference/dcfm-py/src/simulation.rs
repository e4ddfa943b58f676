//! `dcfm.Simulation`: a case in motion (the core's `Simulation`), stepped from Python or
//! run with a progress callback; `dcfm.RunResult`: the histories and final fields of a
//! run as numpy arrays.
//!
//! The steps run without the GIL (other Python threads go on); the callback is called
//! with the GIL every `callback_every` steps and may stop the run by returning `False`.

use std::time::Instant;

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::arrays::{cube, f64_array, matrix, nodes3, vector};
use crate::case::Case;
use crate::errors::IntoPy;

/// A simulation of a case.
#[pyclass(module = "dcfm", name = "Simulation")]
pub struct Simulation {
    sim: dcfm::stage::Simulation,
    label: String,
    end: f64,
    output_nodes: Vec<u32>,
    output_elements: Vec<u32>,
}

/// What `run` was asked to do.
pub struct RunOptions<'py> {
    pub end: Option<f64>,
    pub steps: Option<u64>,
    pub record_every: u64,
    pub nodes: Option<Vec<i64>>,
    pub elements: Option<Vec<i64>>,
    pub callback: Option<Bound<'py, PyAny>>,
    pub callback_every: u64,
    pub threads: Option<usize>,
    /// Record the reference free-field column (every level) after every recorded step.
    pub free_field: bool,
}

/// Histories gathered during a run (plain vectors, filled without the GIL).
#[derive(Default)]
struct Recorder {
    nodes: Vec<usize>,
    elements: Vec<usize>,
    step: Vec<f64>,
    time: Vec<f64>,
    /// kinetic, internal, damping, contact, external, input, residual per record.
    energies: Vec<[f64; 7]>,
    u: Vec<f64>,
    v: Vec<f64>,
    a: Vec<f64>,
    stress: Vec<f64>,
    /// The reference free-field column: record it, its level heights, and per record
    /// the time tⁿ of its last step, displacement and full-step velocity of every level.
    free_field: bool,
    ff_levels: Vec<f64>,
    ff_time: Vec<f64>,
    ff_u: Vec<f64>,
    ff_v: Vec<f64>,
    ff_a: Vec<f64>,
}

/// The energies of `ENERGY_NAMES`, in that order.
fn energy_values(e: &dcfm::stage::Energies) -> [f64; 7] {
    [
        e.kinetic,
        e.internal,
        e.damping,
        e.contact,
        e.external,
        e.input,
        e.residual(),
    ]
}

impl Recorder {
    fn record(&mut self, sim: &dcfm::stage::Simulation) {
        self.step.push(sim.step as f64);
        self.time.push(sim.time);
        self.energies.push(energy_values(&sim.energies));
        for &n in &self.nodes {
            self.u.extend(sim.u[n]);
            self.v.extend(sim.v[n]);
            self.a.extend(sim.a[n]);
        }
        for &el in &self.elements {
            let (_, s) = sim.model.element_strain_stress(el, &sim.u);
            self.stress.extend(s);
        }
        if self.free_field && sim.step > 0 {
            if let Some(c) = sim
                .model
                .boundaries
                .as_ref()
                .and_then(|b| b.reference_column())
            {
                // The column's state is at tⁿ of the step just taken.
                self.ff_time.push(sim.time - sim.dt);
                for l in 0..c.n_levels() {
                    self.ff_u.extend(c.displacement(l));
                    let v = c.velocity(l);
                    self.ff_v.extend(v);
                    // (V^{n+½} − V^{n−½})/Δt, with V^{n−½} = 2 Vⁿ − V^{n+½}.
                    self.ff_a.extend(std::array::from_fn::<f64, 3, _>(|d| {
                        2.0 * (c.v[l][d] - v[d]) / sim.dt
                    }));
                }
            }
        }
    }
}

const ENERGY_NAMES: [&str; 7] = [
    "kinetic", "internal", "damping", "contact", "external", "input", "residual",
];

/// Histories and final fields of a run.
#[pyclass(module = "dcfm", name = "RunResult", frozen, get_all)]
pub struct RunResult {
    /// Time of every record (s), (k,).
    pub time: Py<PyAny>,
    /// Step number of every record, (k,).
    pub step: Py<PyAny>,
    /// Energies at every record (J): dict of (k,) arrays, kinetic, internal, damping,
    /// contact, external, input, residual.
    pub energies: Py<PyAny>,
    /// Recorded nodes and elements (global ids).
    pub nodes: Vec<usize>,
    pub elements: Vec<usize>,
    /// Displacement, velocity (half step V^{n−½}) and acceleration of the recorded nodes,
    /// (k, len(nodes), 3).
    pub displacement: Py<PyAny>,
    pub velocity: Py<PyAny>,
    pub acceleration: Py<PyAny>,
    /// Mean stress of the recorded elements, (k, len(elements), 6), Voigt, Pa.
    pub stress: Py<PyAny>,
    /// Fields at the end of the run (see `Simulation.fields`).
    pub fields: Py<PyAny>,
    /// With `free_field=True` and seismic boundaries: the reference free-field column,
    /// a dict of z (levels,), time (k',: tⁿ of each recorded column step), displacement,
    /// velocity and acceleration (k', levels, 3; full-step velocity at tⁿ, acceleration
    /// (V^{n+½} − V^{n−½})/Δt); otherwise None.
    pub free_field: Py<PyAny>,
    /// Steps done in this run, whether the callback stopped it, its wall time (s) and
    /// element updates per second.
    pub steps: u64,
    pub stopped: bool,
    pub wall_s: f64,
    pub element_updates_per_s: f64,
}

/// A worker pool of `threads` threads (None: rayon's global pool).
pub fn thread_pool(threads: Option<usize>) -> PyResult<Option<rayon::ThreadPool>> {
    match threads {
        Some(0) => Err(PyValueError::new_err("threads: must be ≥ 1")),
        Some(n) => Ok(Some(
            rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .map_err(|e| PyValueError::new_err(format!("threads: {e}")))?,
        )),
        None => Ok(None),
    }
}

impl Simulation {
    /// A simulation at t = 0 from a fresh build of `case` (after its static stage, if it
    /// has one).
    pub fn from_case(py: Python<'_>, case: &Case, dt: Option<f64>) -> PyResult<Self> {
        let built = case.rebuild()?;
        let label = case.label().to_string();
        let (built, static_result) = if built.static_plan.is_some() {
            let (b, r, _) = crate::static_stage::run_stage(py, built, &label, None)?;
            (b, Some(r))
        } else {
            (built, None)
        };
        let dt = dt.unwrap_or(built.dt);
        let sim = match &static_result {
            Some(r) => dcfm::stage::static_stage::start_dynamic(built.model, r, dt, built.safety),
            None => dcfm::stage::Simulation::new(built.model, dt, built.safety),
        }
        .map_err(|e| crate::errors::to_py(e.in_file(&label)))?;
        Ok(Self {
            sim,
            label,
            end: built.end,
            output_nodes: built.output.nodes.clone(),
            output_elements: built.output.elements.clone(),
        })
    }

    fn check_ids(ids: &[i64], n: usize, name: &str) -> PyResult<Vec<usize>> {
        ids.iter()
            .map(|&i| {
                if i >= 0 && (i as usize) < n {
                    Ok(i as usize)
                } else {
                    Err(PyValueError::new_err(format!(
                        "{name}: id {i} out of range 0..{n}"
                    )))
                }
            })
            .collect()
    }

    /// The run loop (shared by `Case.run` and `Simulation.run`).
    pub fn run_with(&mut self, py: Python<'_>, o: RunOptions<'_>) -> PyResult<RunResult> {
        if o.record_every == 0 {
            return Err(PyValueError::new_err("record_every: must be ≥ 1"));
        }
        if o.callback_every == 0 {
            return Err(PyValueError::new_err("callback_every: must be ≥ 1"));
        }
        if let Some(cb) = &o.callback {
            if !cb.is_callable() {
                return Err(pyo3::exceptions::PyTypeError::new_err(
                    "callback: expected a callable f(step, time, energies) or None",
                ));
            }
        }
        let dt = self.sim.dt;
        let target = match (o.steps, o.end) {
            (Some(_), Some(_)) => {
                return Err(PyValueError::new_err(
                    "steps, end: give one of them, not both",
                ))
            }
            (Some(n), None) => self.sim.step + n,
            (None, end) => {
                let end = end.unwrap_or(self.end);
                if !(end.is_finite() && end >= 0.0) {
                    return Err(PyValueError::new_err(format!(
                        "end: {end} must be a finite time ≥ 0 (s)"
                    )));
                }
                (end / dt).ceil() as u64
            }
        };
        let n_nodes = self.sim.model.mesh.n_nodes();
        let n_elements = self.sim.model.n_elements();
        let default_nodes: Vec<i64> = self.output_nodes.iter().map(|&x| x as i64).collect();
        let default_elements: Vec<i64> = self.output_elements.iter().map(|&x| x as i64).collect();
        let mut rec = Recorder {
            nodes: Self::check_ids(
                o.nodes.as_deref().unwrap_or(&default_nodes),
                n_nodes,
                "nodes",
            )?,
            elements: Self::check_ids(
                o.elements.as_deref().unwrap_or(&default_elements),
                n_elements,
                "elements",
            )?,
            ..Default::default()
        };
        if o.free_field {
            let column = self
                .sim
                .model
                .boundaries
                .as_ref()
                .and_then(|b| b.reference_column());
            let Some(column) = column else {
                return Err(PyValueError::new_err(format!(
                    "free_field: {} has no free-field column (it needs a [seismic] input \
                     through [[boundary.absorbing]] … input = true, docs/boundaries.md)",
                    self.label
                )));
            };
            rec.free_field = true;
            rec.ff_levels = column.levels.clone();
        }
        let pool = thread_pool(o.threads)?;
        rec.record(&self.sim);
        let start_step = self.sim.step;
        let t0 = Instant::now();
        let mut stopped = false;
        while self.sim.step < target {
            let chunk_end = if o.callback.is_some() {
                (self.sim.step / o.callback_every + 1) * o.callback_every
            } else {
                target
            }
            .min(target);
            let sim = &mut self.sim;
            let rec_ref = &mut rec;
            let every = o.record_every;
            let mut work = move || -> dcfm::Result<()> {
                while sim.step < chunk_end {
                    sim.step()?;
                    if sim.step.is_multiple_of(every) || sim.step == target {
                        rec_ref.record(sim);
                    }
                }
                Ok(())
            };
            let result = py.detach(|| match &pool {
                Some(p) => p.install(work),
                None => work(),
            });
            result.map_err(|e| crate::errors::to_py(e.in_file(&self.label)))?;
            py.check_signals()?;
            if let Some(cb) = &o.callback {
                let ret =
                    cb.call1((self.sim.step, self.sim.time, energies_dict(py, &self.sim)?))?;
                if let Ok(false) = ret.extract::<bool>() {
                    stopped = true;
                    break;
                }
            }
        }
        if stopped && rec.step.last().copied() != Some(self.sim.step as f64) {
            rec.record(&self.sim);
        }
        let wall = t0.elapsed().as_secs_f64();
        let steps = self.sim.step - start_step;
        let k = rec.time.len();
        let energies = PyDict::new(py);
        for (i, name) in ENERGY_NAMES.iter().enumerate() {
            energies.set_item(
                name,
                vector(py, rec.energies.iter().map(|e| e[i]).collect()),
            )?;
        }
        let nn = rec.nodes.len();
        let ne = rec.elements.len();
        let free_field = if rec.free_field {
            let d = PyDict::new(py);
            let (kf, nl) = (rec.ff_time.len(), rec.ff_levels.len());
            d.set_item("z", vector(py, std::mem::take(&mut rec.ff_levels)))?;
            d.set_item("time", vector(py, std::mem::take(&mut rec.ff_time)))?;
            d.set_item(
                "displacement",
                cube(py, (kf, nl, 3), std::mem::take(&mut rec.ff_u)),
            )?;
            d.set_item(
                "velocity",
                cube(py, (kf, nl, 3), std::mem::take(&mut rec.ff_v)),
            )?;
            d.set_item(
                "acceleration",
                cube(py, (kf, nl, 3), std::mem::take(&mut rec.ff_a)),
            )?;
            d.into_any().unbind()
        } else {
            py.None()
        };
        Ok(RunResult {
            time: vector(py, rec.time).into_any().unbind(),
            step: vector(py, rec.step).into_any().unbind(),
            energies: energies.into_any().unbind(),
            displacement: cube(py, (k, nn, 3), rec.u).into_any().unbind(),
            velocity: cube(py, (k, nn, 3), rec.v).into_any().unbind(),
            acceleration: cube(py, (k, nn, 3), rec.a).into_any().unbind(),
            stress: cube(py, (k, ne, 6), rec.stress).into_any().unbind(),
            fields: self.fields(py)?.into_any().unbind(),
            free_field,
            nodes: rec.nodes,
            elements: rec.elements,
            steps,
            stopped,
            wall_s: wall,
            element_updates_per_s: steps as f64 * n_elements as f64 / wall.max(1e-12),
        })
    }
}

/// The energies of the last completed step as a dict.
fn energies_dict<'py>(
    py: Python<'py>,
    sim: &dcfm::stage::Simulation,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for (name, v) in ENERGY_NAMES.iter().zip(energy_values(&sim.energies)) {
        d.set_item(name, v)?;
    }
    d.set_item("initial_kinetic", sim.energies.initial_kinetic)?;
    Ok(d)
}

#[pymethods]
impl Simulation {
    /// Time step (s).
    #[getter]
    fn dt(&self) -> f64 {
        self.sim.dt
    }

    /// Time tⁿ (s).
    #[getter]
    fn time(&self) -> f64 {
        self.sim.time
    }

    /// Steps done.
    #[getter]
    fn step_count(&self) -> u64 {
        self.sim.step
    }

    /// Displacements Uⁿ, (n_nodes, 3) (m).
    #[getter]
    fn displacement<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        nodes3(py, &self.sim.u).into_any()
    }

    /// Half-step velocities V^{n−½}, (n_nodes, 3) (m/s).
    #[getter]
    fn velocity<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        nodes3(py, &self.sim.v).into_any()
    }

    /// Accelerations of the last step, (n_nodes, 3) (m/s²).
    #[getter]
    fn acceleration<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        nodes3(py, &self.sim.a).into_any()
    }

    /// Lumped nodal masses (kg).
    #[getter]
    fn mass<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        vector(py, self.sim.model.mass.clone()).into_any()
    }

    /// Energies at the last completed step (J).
    #[getter]
    fn energies<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        energies_dict(py, &self.sim)
    }

    /// Exact elastic strain energy of the current displacements (linear elastic regions).
    fn elastic_strain_energy(&self) -> f64 {
        self.sim.elastic_strain_energy()
    }

    /// Replace the velocities (an initial velocity field no node set describes), (n_nodes,
    /// 3); fixed DOFs stay at zero. The energy account starts afresh from them.
    fn set_velocity(&mut self, velocity: &Bound<'_, PyAny>) -> PyResult<()> {
        let n = self.sim.u.len();
        let (data, _) = f64_array(velocity, "velocity", &[Some(n), Some(3)])?;
        let fixed = &self.sim.model.constraints.fixed;
        for (i, v) in self.sim.v.iter_mut().enumerate() {
            for d in 0..3 {
                v[d] = if fixed[i] & (1 << d) != 0 {
                    0.0
                } else {
                    data[3 * i + d]
                };
            }
        }
        self.sim.restart_energy_account();
        Ok(())
    }

    /// Advance `n` steps (without the GIL).
    #[pyo3(signature = (n = 1, threads = None))]
    fn step(&mut self, py: Python<'_>, n: u64, threads: Option<usize>) -> PyResult<()> {
        let label = self.label.clone();
        let sim = &mut self.sim;
        let work = move || sim.run_steps(n);
        let r = match threads {
            Some(0) => return Err(PyValueError::new_err("threads: must be ≥ 1")),
            Some(t) => {
                let pool = rayon::ThreadPoolBuilder::new()
                    .num_threads(t)
                    .build()
                    .map_err(|e| PyValueError::new_err(format!("threads: {e}")))?;
                py.detach(|| pool.install(work))
            }
            None => py.detach(work),
        };
        r.map_err(|e| e.in_file(&label)).py_err()
    }

    /// Run to `end` (default: the case's end time) or for `steps` more steps, recording
    /// time, energies, the displacement/velocity/acceleration of `nodes` and the stress of
    /// `elements` (default: the case's `[output]` lists) every `record_every` steps and
    /// at the last one. `callback(step, time, energies)` is called every
    /// `callback_every` steps; returning `False` stops the run. `threads` sets the worker
    /// threads (default: all cores; results do not depend on it).
    #[pyo3(signature = (*, end = None, steps = None, record_every = 1, nodes = None,
        elements = None, callback = None, callback_every = 100, threads = None,
        free_field = false))]
    #[allow(clippy::too_many_arguments)]
    fn run(
        &mut self,
        py: Python<'_>,
        end: Option<f64>,
        steps: Option<u64>,
        record_every: u64,
        nodes: Option<Vec<i64>>,
        elements: Option<Vec<i64>>,
        callback: Option<Bound<'_, PyAny>>,
        callback_every: u64,
        threads: Option<usize>,
        free_field: bool,
    ) -> PyResult<RunResult> {
        self.run_with(
            py,
            RunOptions {
                end,
                steps,
                record_every,
                nodes,
                elements,
                callback,
                callback_every,
                threads,
                free_field,
            },
        )
    }

    /// The reference free-field column now (None without seismic boundaries): z
    /// (levels,), displacement and velocity (levels, 3) at tⁿ of its last step.
    fn free_field_column<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyDict>>> {
        let Some(c) = self
            .sim
            .model
            .boundaries
            .as_ref()
            .and_then(|b| b.reference_column())
        else {
            return Ok(None);
        };
        let d = PyDict::new(py);
        let n = c.n_levels();
        d.set_item("z", vector(py, c.levels.clone()))?;
        let u: Vec<[f64; 3]> = (0..n).map(|l| c.displacement(l)).collect();
        let v: Vec<[f64; 3]> = (0..n).map(|l| c.velocity(l)).collect();
        d.set_item("displacement", nodes3(py, &u))?;
        d.set_item("velocity", nodes3(py, &v))?;
        Ok(Some(d))
    }

    /// Element and node fields of the current state: displacement, velocity, acceleration
    /// (n_nodes, 3); strain, stress (n_elements, 6, element means); region (n_elements,);
    /// damage, damage_tension, damage_compression, kappa_tension, kappa_compression
    /// (n_elements,) and plastic_strain (n_elements, 6) (zero for materials without
    /// damage); with contact interfaces contact_state (n_nodes,: 0 bonded, 1 stick,
    /// 2 sliding, 3 separated, +10 point-to-surface, −1 on no interface), contact_gap,
    /// contact_slip (n_nodes, 3), contact_slip_accumulated, contact_normal_force,
    /// contact_tangential_force (n_nodes, 3).
    fn fields<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let sim = &self.sim;
        let model = &sim.model;
        let ne = model.n_elements();
        let ef = dcfm::element::fields::ElementFields::of(model, &sim.u);
        let d = PyDict::new(py);
        d.set_item("displacement", nodes3(py, &sim.u))?;
        d.set_item("velocity", nodes3(py, &sim.v))?;
        d.set_item("acceleration", nodes3(py, &sim.a))?;
        d.set_item("strain", matrix(py, ne, 6, ef.strain.clone()))?;
        d.set_item("stress", matrix(py, ne, 6, ef.stress.clone()))?;
        d.set_item("region", vector(py, ef.region.clone()))?;
        for (k, name) in [
            "damage",
            "damage_tension",
            "damage_compression",
            "kappa_tension",
            "kappa_compression",
        ]
        .iter()
        .enumerate()
        {
            d.set_item(name, vector(py, ef.damage_values(k, 1)))?;
        }
        d.set_item("plastic_strain", matrix(py, ne, 6, ef.damage_values(5, 6)))?;
        if let Some(c) = &model.contact {
            let n = model.mesh.n_nodes();
            for (name, comps, values) in c.node_fields(n) {
                if comps == 1 {
                    d.set_item(name, vector(py, values))?;
                } else {
                    d.set_item(name, matrix(py, n, comps, values))?;
                }
            }
        }
        Ok(d)
    }

    fn __repr__(&self) -> String {
        format!(
            "Simulation({:?}: step {}, t = {:.6e} s, dt = {:.4e} s)",
            self.label, self.sim.step, self.sim.time, self.sim.dt
        )
    }
}
