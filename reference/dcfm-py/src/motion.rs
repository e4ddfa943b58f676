//! Ground motions from Python (`dcfm::motion`, docs/motion.md): `dcfm.read_motion` (the
//! core's readers), `dcfm.Motion.from_arrays` (samples a program made — numpy arrays, or
//! ObsPy traces through `Motion.from_obspy`, which reads SAC, MiniSEED and the rest),
//! `dcfm.synthetic_motion`, `Motion.process` (window, baseline, taper, Butterworth,
//! resampling, end correction, scaling), the exact integrals `velocity()` /
//! `displacement()`, and the measures (`dcfm.response_spectrum`, Arias, D5–95, Fourier).
//!
//! A `Motion` is the core's `GroundMotion`: every component's acceleration (m/s²) and its
//! exact integrals from rest. A motion read or made here is unprocessed (baseline "none");
//! `process` applies the case file's processing to its acceleration and returns a new
//! motion whose provenance lists every step. A motion given to `Case.from_*(…,
//! motions={"name": m})` is used by the case's time functions like a `[motions.NAME]`.

use std::path::PathBuf;
use std::sync::Arc;

use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use dcfm::motion::measures;
use dcfm::motion::processing::Baseline;
use dcfm::motion::{
    process, AccelUnits, Axis, Format, GroundMotion, ProcessingOptions, ReadOptions, Record,
    RecordComponent,
};

use crate::arrays::{f64_array, matrix, vector};
use crate::errors::IntoPy;
use crate::toml_value::dict_to_toml;

/// A ground motion: one to three acceleration components on one uniform grid.
#[pyclass(module = "dcfm", name = "Motion", frozen)]
pub struct Motion {
    pub inner: Arc<GroundMotion>,
}

/// Options that leave a record as it is (no baseline, no filter): the motion as read.
fn unprocessed() -> ProcessingOptions {
    ProcessingOptions {
        baseline: Some(Baseline::None),
        ..ProcessingOptions::default()
    }
}

/// The record behind a motion (its acceleration and header facts), to process again.
fn record_of(m: &GroundMotion) -> Record {
    Record {
        source: m.source.clone(),
        format: m.format,
        station: m.station.clone(),
        description: m.description.clone(),
        units: m.original_units,
        dt: m.dt,
        components: m
            .components
            .iter()
            .map(|c| RecordComponent {
                name: c.name.clone(),
                axis: c.axis,
                acceleration: c.acceleration.clone(),
                header_peak: None,
            })
            .collect(),
    }
}

fn parse_units(units: &str, argument: &str) -> PyResult<AccelUnits> {
    AccelUnits::parse(units).ok_or_else(|| {
        PyValueError::new_err(format!(
            "{argument}: unknown units {units:?} (expected one of {})",
            AccelUnits::NAMES
        ))
    })
}

fn parse_axis(name: &str, argument: &str) -> PyResult<Axis> {
    Axis::parse(name).ok_or_else(|| {
        PyValueError::new_err(format!(
            "{argument}: unknown axis {name:?} (expected \"x\", \"y\" or \"z\")"
        ))
    })
}

/// Check that axes are distinct (two components cannot drive one axis).
fn check_distinct(components: &[RecordComponent], argument: &str) -> PyResult<()> {
    for (i, a) in components.iter().enumerate() {
        for b in &components[..i] {
            if a.axis.is_some() && a.axis == b.axis {
                return Err(PyValueError::new_err(format!(
                    "{argument}: components {:?} and {:?} both drive axis {}",
                    b.name,
                    a.name,
                    a.axis.map(Axis::name).unwrap_or("-")
                )));
            }
        }
    }
    Ok(())
}

impl Motion {
    fn wrap(m: GroundMotion) -> Self {
        Self { inner: Arc::new(m) }
    }

    /// The motion of `record` with `options` (`label`/`field` name it in errors).
    fn processed(
        record: &Record,
        name: &str,
        options: &ProcessingOptions,
        label: &str,
        field: &str,
        before: &[String],
    ) -> PyResult<Self> {
        let mut m = process(record, name, options, label, field).py_err()?;
        if !before.is_empty() {
            // Keep the earlier steps; drop this pass's "read …" line and the earlier
            // "integrated …" line (the new one closes the list).
            let mut lines: Vec<String> = before
                .iter()
                .filter(|l| !l.starts_with("integrated"))
                .cloned()
                .collect();
            lines.extend(m.provenance.drain(..).skip(1));
            m.provenance = lines;
        }
        Ok(Self::wrap(m))
    }

    /// (n,) for one component, (n, k) for k.
    fn columns<'py>(
        &self,
        py: Python<'py>,
        pick: impl Fn(&dcfm::motion::MotionComponent) -> &[f64],
    ) -> Bound<'py, PyAny> {
        let n = self.inner.npts();
        let cs = &self.inner.components;
        if cs.len() == 1 {
            return vector(py, pick(&cs[0])[..n].to_vec()).into_any();
        }
        let mut flat = Vec::with_capacity(n * cs.len());
        for i in 0..n {
            for c in cs {
                flat.push(pick(c)[i]);
            }
        }
        matrix(py, n, cs.len(), flat).into_any()
    }

    /// The component called `name` (axis or record name), or the only one.
    fn pick(&self, component: Option<&str>) -> PyResult<Vec<&dcfm::motion::MotionComponent>> {
        match component {
            None => Ok(self.inner.components.iter().map(|c| c.as_ref()).collect()),
            Some(name) => self
                .inner
                .component_named(name)
                .map(|c| vec![c.as_ref()])
                .ok_or_else(|| {
                    PyValueError::new_err(format!(
                        "component: no component {name:?} (have {:?})",
                        self.component_names()
                    ))
                }),
        }
    }

    fn component_names(&self) -> Vec<String> {
        self.inner
            .components
            .iter()
            .map(|c| c.name.clone())
            .collect()
    }
}

#[pymethods]
impl Motion {
    /// A motion from acceleration samples: `acceleration` (n,) or (n, k ≤ 3), step `dt`
    /// (s), `units` ("g", "gal" = "cm/s2", "m/s2"); `components` names them (default x, y,
    /// z), `axes` gives the model axis of each ("x"/"y"/"z"/None; default: from the name,
    /// as for records: EW → x, NS → y, UD/HNZ → z).
    #[staticmethod]
    #[pyo3(signature = (acceleration, dt, units, *, components = None, axes = None,
        name = "arrays".to_string(), station = String::new(), description = String::new(),
        source = "arrays".to_string()))]
    #[allow(clippy::too_many_arguments)]
    fn from_arrays(
        acceleration: &Bound<'_, PyAny>,
        dt: f64,
        units: &str,
        components: Option<Vec<String>>,
        axes: Option<Vec<Option<String>>>,
        name: String,
        station: String,
        description: String,
        source: String,
    ) -> PyResult<Self> {
        if !(dt.is_finite() && dt > 0.0) {
            return Err(PyValueError::new_err(format!(
                "dt: {dt} must be a finite step > 0 (s)"
            )));
        }
        let units = parse_units(units, "units")?;
        let (data, shape) = match f64_array(acceleration, "acceleration", &[None]) {
            Ok(x) => x,
            Err(_) => f64_array(acceleration, "acceleration", &[None, None])?,
        };
        let (n, k) = if shape.len() == 1 {
            (shape[0], 1)
        } else {
            (shape[0], shape[1])
        };
        if !(1..=3).contains(&k) {
            return Err(PyValueError::new_err(format!(
                "acceleration: expected shape (n,) or (n, k) with k ≤ 3 components, got {shape:?}"
            )));
        }
        if n < 2 {
            return Err(PyValueError::new_err(format!(
                "acceleration: expected at least 2 samples, got {n}"
            )));
        }
        let names = match components {
            Some(c) if c.len() != k => {
                return Err(PyValueError::new_err(format!(
                    "components: {} names for {k} component(s)",
                    c.len()
                )))
            }
            Some(c) => c,
            None => ["x", "y", "z"][..k].iter().map(|s| s.to_string()).collect(),
        };
        let axes: Vec<Option<Axis>> = match axes {
            Some(a) if a.len() != k => {
                return Err(PyValueError::new_err(format!(
                    "axes: {} axes for {k} component(s)",
                    a.len()
                )))
            }
            Some(a) => a
                .iter()
                .map(|x| x.as_deref().map(|s| parse_axis(s, "axes")).transpose())
                .collect::<PyResult<_>>()?,
            None => names.iter().map(|s| Axis::guess(s)).collect(),
        };
        let factor = units.to_si();
        let comps: Vec<RecordComponent> = (0..k)
            .map(|j| RecordComponent {
                name: names[j].clone(),
                axis: axes[j],
                acceleration: (0..n).map(|i| data[i * k + j] * factor).collect(),
                header_peak: None,
            })
            .collect();
        check_distinct(&comps, "axes")?;
        let record = Record {
            source,
            format: Format::Arrays,
            station,
            description,
            units,
            dt,
            components: comps,
        };
        Self::processed(
            &record,
            &name,
            &unprocessed(),
            "<Motion.from_arrays>",
            "process",
            &[],
        )
    }

    /// A motion from ObsPy: a `Trace`, or a `Stream` (or list) of up to three traces of
    /// one station with the same sampling step and start time (longer ones are cut to the
    /// shortest). This is how SAC, MiniSEED and ObsPy's other formats reach dcfm
    /// (`obspy.read(path)`). Samples are `trace.data × stats.calib` (`apply_calib`);
    /// `units` ("g", "gal", "m/s2") is required unless the format states them: K-NET /
    /// KiK-net traces (ObsPy's `calib` turns their counts into m/s²). Component names are
    /// the channel codes (axes guessed from them: HNE → x, HNN → y, HNZ → z; or `axes`).
    #[staticmethod]
    #[pyo3(signature = (data, units = None, *, axes = None, name = None, apply_calib = true))]
    fn from_obspy(
        data: &Bound<'_, PyAny>,
        units: Option<&str>,
        axes: Option<Vec<Option<String>>>,
        name: Option<String>,
        apply_calib: bool,
    ) -> PyResult<Self> {
        let traces: Vec<Bound<'_, PyAny>> = if data.hasattr("stats")? && data.hasattr("data")? {
            vec![data.clone()]
        } else {
            data.try_iter()
                .map_err(|_| {
                    PyTypeError::new_err(
                        "data: expected an ObsPy Trace or Stream (or a list of traces)",
                    )
                })?
                .collect::<PyResult<_>>()?
        };
        if !(1..=3).contains(&traces.len()) {
            return Err(PyValueError::new_err(format!(
                "data: expected 1 to 3 traces, got {}",
                traces.len()
            )));
        }
        let mut names = Vec::new();
        let mut series: Vec<Vec<f64>> = Vec::new();
        let mut ids = Vec::new();
        let mut formats = Vec::new();
        let mut dt0 = 0.0;
        let mut station = String::new();
        for (i, tr) in traces.iter().enumerate() {
            let arg = format!("data[{i}]");
            let stats = tr.getattr("stats").map_err(|_| {
                PyTypeError::new_err(format!("{arg}: expected an ObsPy Trace (no stats)"))
            })?;
            let dt: f64 = stats.getattr("delta")?.extract()?;
            let calib: f64 = if apply_calib {
                stats.getattr("calib")?.extract()?
            } else {
                1.0
            };
            let fmt: String = stats
                .getattr("_format")
                .and_then(|f| f.extract())
                .unwrap_or_default();
            if i == 0 {
                dt0 = dt;
                station = stats.getattr("station")?.extract()?;
            } else {
                if (dt - dt0).abs() > 1e-9 * dt0 {
                    return Err(PyValueError::new_err(format!(
                        "{arg}: sampling step {dt} s differs from the first trace's {dt0} s"
                    )));
                }
                let shift: f64 = stats
                    .getattr("starttime")?
                    .sub(traces[0].getattr("stats")?.getattr("starttime")?)?
                    .extract()?;
                if shift.abs() > 0.5 * dt0 {
                    return Err(PyValueError::new_err(format!(
                        "{arg}: starts {shift} s after the first trace (trim the stream to a common start)"
                    )));
                }
            }
            let (mut x, _) = f64_array(&tr.getattr("data")?, &format!("{arg}.data"), &[None])?;
            if calib != 1.0 {
                x.iter_mut().for_each(|v| *v *= calib);
            }
            series.push(x);
            names.push(stats.getattr("channel")?.extract::<String>()?);
            ids.push(tr.getattr("id")?.extract::<String>()?);
            formats.push(fmt);
        }
        let units = match units {
            Some(u) => u.to_string(),
            None if apply_calib && formats.iter().all(|f| f == "KNET") => "m/s2".to_string(),
            None => {
                return Err(PyValueError::new_err(format!(
                    "units: required for {} trace(s) (the format does not state acceleration \
                     units; give \"g\", \"gal\" or \"m/s2\" of the samples × calib)",
                    formats.join("/")
                )))
            }
        };
        let n = series.iter().map(Vec::len).min().unwrap_or(0);
        let k = series.len();
        let mut flat = Vec::with_capacity(n * k);
        for i in 0..n {
            for s in &series {
                flat.push(s[i]);
            }
        }
        let py = data.py();
        let arr = matrix(py, n, k, flat);
        let source = format!("ObsPy {} trace(s) {}", formats.join("/"), ids.join(" + "));
        let name = name.unwrap_or_else(|| ids[0].clone());
        let mut m = Self::from_arrays(
            arr.as_any(),
            dt0,
            &units,
            Some(names),
            axes,
            name,
            station,
            String::new(),
            source,
        )?;
        if let Some(inner) = Arc::get_mut(&mut m.inner) {
            inner.provenance.insert(
                0,
                format!(
                    "from ObsPy: {} trace(s){}, {n} samples",
                    k,
                    if apply_calib {
                        ", samples × stats.calib"
                    } else {
                        ""
                    }
                ),
            );
        }
        Ok(m)
    }

    /// Name (file stem, or the name given).
    #[getter]
    fn name(&self) -> &str {
        &self.inner.name
    }

    /// File(s) or program it came from.
    #[getter]
    fn source(&self) -> &str {
        &self.inner.source
    }

    /// Format name: text, csv, at2, knet, cosmos, smc, synthetic or arrays.
    #[getter]
    fn format(&self) -> &str {
        self.inner.format.name()
    }

    #[getter]
    fn station(&self) -> &str {
        &self.inner.station
    }

    #[getter]
    fn description(&self) -> &str {
        &self.inner.description
    }

    /// Units the file stored ("g", "cm/s²", "m/s²"); every array here is in SI.
    #[getter]
    fn units(&self) -> String {
        self.inner.original_units.to_string()
    }

    /// Step (s).
    #[getter]
    fn dt(&self) -> f64 {
        self.inner.dt
    }

    /// Samples per component.
    #[getter]
    fn npts(&self) -> usize {
        self.inner.npts()
    }

    /// Time of the last sample (s).
    #[getter]
    fn duration(&self) -> f64 {
        self.inner.duration()
    }

    /// Component names, in order.
    #[getter]
    fn components(&self) -> Vec<String> {
        self.component_names()
    }

    /// Model axis of each component ("x", "y", "z" or None).
    #[getter]
    fn axes(&self) -> Vec<Option<&'static str>> {
        self.inner
            .components
            .iter()
            .map(|c| c.axis.map(Axis::name))
            .collect()
    }

    /// Every step that made this motion (reading, processing, integration).
    #[getter]
    fn provenance(&self) -> Vec<String> {
        self.inner.provenance.clone()
    }

    /// Sample times i·dt (s), (n,).
    #[getter]
    fn time<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        let dt = self.inner.dt;
        vector(py, (0..self.inner.npts()).map(|i| i as f64 * dt).collect()).into_any()
    }

    /// Acceleration (m/s²): (n,) for one component, (n, k) for k.
    #[getter]
    fn acceleration<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        self.columns(py, |c| &c.acceleration)
    }

    /// Velocity (m/s) from rest, exact for the piecewise-linear acceleration:
    /// v_{i+1} = v_i + Δt (a_i + a_{i+1})/2.
    fn velocity<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        self.columns(py, |c| &c.velocity)
    }

    /// Displacement (m) from rest: u_{i+1} = u_i + Δt v_i + Δt² (2a_i + a_{i+1})/6.
    fn displacement<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        self.columns(py, |c| &c.displacement)
    }

    /// Process the acceleration with the options of `[motions.NAME.processing]`
    /// (docs/motion.md §2): window, baseline ("none" | "mean" | "polynomial"; default
    /// "mean", as for a record in a case), baseline_order, taper, highpass, lowpass,
    /// filter_order, zero_phase, pad, resample_dt, zero_end, target_pga. Returns a new
    /// motion; errors name `process.FIELD`.
    #[pyo3(signature = (**options))]
    fn process(&self, options: Option<&Bound<'_, PyDict>>) -> PyResult<Self> {
        let opts: ProcessingOptions = match options {
            None => ProcessingOptions::default(),
            Some(d) => {
                let text = dict_to_toml(d.as_any(), "options")?;
                toml::from_str(&text).map_err(|e| {
                    crate::errors::to_py(dcfm::DcfmError::Parse {
                        file: "<Motion.process>".into(),
                        message: e.to_string().trim_end().to_string(),
                    })
                })?
            }
        };
        let label = format!("<Motion.process of {}>", self.inner.name);
        Self::processed(
            &record_of(&self.inner),
            &self.inner.name,
            &opts,
            &label,
            "process",
            &self.inner.provenance,
        )
    }

    /// The motion of one component (by axis or record name).
    fn component(&self, name: &str) -> PyResult<Self> {
        let c = self.pick(Some(name))?[0];
        let mut m = (*self.inner).clone();
        m.components = vec![Arc::new(c.clone())];
        Ok(Self::wrap(m))
    }

    /// Peak |a|, |v|, |u| and their times per component: dict name → {pga, pga_time, pgv,
    /// pgv_time, pgd, pgd_time, arias (m/s), d5_95 (s, or None)}.
    fn summary<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let out = PyDict::new(py);
        for s in dcfm::motion::summary::summarize(&self.inner) {
            let d = PyDict::new(py);
            d.set_item("axis", &s.axis)?;
            d.set_item("pga", s.pga.value)?;
            d.set_item("pga_time", s.pga.time)?;
            d.set_item("pgv", s.pgv.value)?;
            d.set_item("pgv_time", s.pgv.time)?;
            d.set_item("pgd", s.pgd.value)?;
            d.set_item("pgd_time", s.pgd.time)?;
            d.set_item("arias", s.arias)?;
            d.set_item("d5_95", s.d5_95.map(|x| x.2))?;
            out.set_item(&s.name, d)?;
        }
        Ok(out)
    }

    /// Husid curve ∫₀ᵗa² / ∫₀ᵀa² of a component (default: the only one), (n,).
    #[pyo3(signature = (component = None))]
    fn husid<'py>(&self, py: Python<'py>, component: Option<&str>) -> PyResult<Bound<'py, PyAny>> {
        let c = self.single(component)?;
        Ok(vector(py, measures::husid(&c.acceleration, c.dt)).into_any())
    }

    /// Fourier amplitude |A(f_k)| = Δt |Σ a_n e^{−2πikn/N}| of a component: (f, amplitude).
    #[pyo3(signature = (component = None))]
    fn fourier_amplitude<'py>(
        &self,
        py: Python<'py>,
        component: Option<&str>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
        let c = self.single(component)?;
        let (f, a) = measures::fourier_amplitude(&c.acceleration, c.dt);
        Ok((vector(py, f).into_any(), vector(py, a).into_any()))
    }

    fn __repr__(&self) -> String {
        format!(
            "Motion({:?}: {} ({}), {} component(s) {:?}, {} samples, dt = {} s)",
            self.inner.name,
            self.inner.source,
            self.inner.format,
            self.inner.components.len(),
            self.component_names(),
            self.inner.npts(),
            self.inner.dt
        )
    }
}

impl Motion {
    fn single(&self, component: Option<&str>) -> PyResult<&dcfm::motion::MotionComponent> {
        let cs = self.pick(component)?;
        if cs.len() != 1 {
            return Err(PyValueError::new_err(format!(
                "component: the motion has {} components {:?}; name one",
                cs.len(),
                self.component_names()
            )));
        }
        Ok(cs[0])
    }
}

/// Read a record file with the core's readers (format "auto", "text", "csv", "at2",
/// "knet", "cosmos", "smc"; units and dt where the file does not state them; `components`
/// the axis of each component in reading order). The motion is as read: converted to
/// m/s², no baseline or filter (use `process`).
#[pyfunction]
#[pyo3(signature = (path, format = None, *, units = None, dt = None, components = None, name = None))]
pub fn read_motion(
    path: PathBuf,
    format: Option<&str>,
    units: Option<&str>,
    dt: Option<f64>,
    components: Option<Vec<String>>,
    name: Option<String>,
) -> PyResult<Motion> {
    let label = path.display().to_string();
    let format = match format {
        None => None,
        Some(f) => Format::parse(f).map_err(|e| PyValueError::new_err(format!("format: {e}")))?,
    };
    let units = units.map(|u| parse_units(u, "units")).transpose()?;
    let options = ReadOptions { format, units, dt };
    let mut record = dcfm::motion::read_file(&path, &options).py_err()?;
    if let Some(axes) = components {
        if axes.len() != record.components.len() {
            return Err(PyValueError::new_err(format!(
                "components: {} axes for the {} component(s) of {label}",
                axes.len(),
                record.components.len()
            )));
        }
        for (c, a) in record.components.iter_mut().zip(&axes) {
            c.axis = Some(parse_axis(a, "components")?);
        }
    }
    check_distinct(&record.components, "components")?;
    let name = name.unwrap_or_else(|| {
        path.file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_else(|| "motion".into())
    });
    Motion::processed(&record, &name, &unprocessed(), &label, "process", &[])
}

/// A seeded synthetic motion (`synthetic = { … }` of a case, docs/motion.md §4), e.g.
/// `{"preset": "wolong", "seed": 1}`; generated and processed as a case would.
#[pyfunction]
#[pyo3(signature = (spec, name = "synthetic".to_string()))]
pub fn synthetic_motion(spec: &Bound<'_, PyAny>, name: String) -> PyResult<Motion> {
    let text = dict_to_toml(spec, "spec")?;
    let syn: dcfm::motion::SyntheticSpec = toml::from_str(&text).map_err(|e| {
        crate::errors::to_py(dcfm::DcfmError::Parse {
            file: "<synthetic_motion>".into(),
            message: e.to_string().trim_end().to_string(),
        })
    })?;
    let (record, provenance) = syn
        .parameters("<synthetic_motion>", "spec")
        .py_err()?
        .generate();
    let mut m = process(
        &record,
        &name,
        &ProcessingOptions::default(),
        "<synthetic_motion>",
        "process",
    )
    .py_err()?;
    let mut lines = provenance;
    lines.append(&mut m.provenance);
    m.provenance = lines;
    Ok(Motion::wrap(m))
}

/// Elastic response spectrum (Nigam–Jennings, exact for piecewise-linear acceleration) of
/// `motion` at `periods` (s) and `damping` (ratio): dict of period, sd (m), sv (m/s), sa
/// (absolute, m/s²), psv, psa; (p,) for one component (or `component`), (p, k) for k.
#[pyfunction]
#[pyo3(signature = (motion, periods, damping = 0.05, *, component = None))]
pub fn response_spectrum<'py>(
    py: Python<'py>,
    motion: &Bound<'py, PyAny>,
    periods: &Bound<'py, PyAny>,
    damping: f64,
    component: Option<&str>,
) -> PyResult<Bound<'py, PyDict>> {
    let motion = motion.cast::<Motion>().map_err(|_| {
        PyTypeError::new_err(format!(
            "motion: expected a dcfm.Motion, got a {}",
            motion
                .get_type()
                .name()
                .map(|n| n.to_string())
                .unwrap_or_default()
        ))
    })?;
    let motion = motion.get();
    let (periods, _) = f64_array(periods, "periods", &[None])?;
    if let Some(p) = periods.iter().find(|p| **p < 0.0) {
        return Err(PyValueError::new_err(format!(
            "periods: {p} must be ≥ 0 (s)"
        )));
    }
    if !(damping.is_finite() && damping >= 0.0) {
        return Err(PyValueError::new_err(format!(
            "damping: {damping} must be a ratio ≥ 0"
        )));
    }
    let comps = motion.pick(component)?;
    let spectra: Vec<Vec<measures::SpectrumPoint>> = py.detach(|| {
        comps
            .iter()
            .map(|c| measures::response_spectrum(&c.acceleration, c.dt, &periods, damping))
            .collect()
    });
    let d = PyDict::new(py);
    let p = periods.len();
    let k = spectra.len();
    d.set_item("period", vector(py, periods.clone()))?;
    type Get = fn(&measures::SpectrumPoint) -> f64;
    let items: [(&str, Get); 5] = [
        ("sd", |s| s.sd),
        ("sv", |s| s.sv),
        ("sa", |s| s.sa),
        ("psv", |s| s.psv),
        ("psa", |s| s.psa),
    ];
    for (key, get) in items {
        if k == 1 {
            d.set_item(key, vector(py, spectra[0].iter().map(get).collect()))?;
        } else {
            let mut flat = Vec::with_capacity(p * k);
            for i in 0..p {
                for s in &spectra {
                    flat.push(get(&s[i]));
                }
            }
            d.set_item(key, matrix(py, p, k, flat))?;
        }
    }
    Ok(d)
}
