//! Checkpoints of a running simulation, so that long runs can be resumed: displacements,
//! half-step velocities, accelerations, energies, every integration-point state and the
//! state of every contact interface, the absorbing boundaries and the anchor bars, as
//! little-endian bytes. The core only serialises (the file around the blocks, with its
//! checksum and case hash, is [`crate::stage::checkpoint_seal`]); the application writes
//! the bytes to a file (atomically) and reads them back.

use std::io::Write;

use crate::error::{DcfmError, Result};
use crate::stage::{Energies, Simulation};

/// Magic of the dynamic state block. Version 4 added the anchor bars' state (plastic
/// strains, bond–slip nodes); from file format DCFMCKP5 the block sits inside the sealed
/// file of [`crate::stage::checkpoint_seal`], which checks versions, case and checksum.
const MAGIC: &[u8; 8] = b"DCFMDYN5";

fn put_f64s(w: &mut impl Write, xs: &[f64]) -> std::io::Result<()> {
    for x in xs {
        w.write_all(&x.to_le_bytes())?;
    }
    Ok(())
}

/// Number of values of [`energies_vec`].
const N_ENERGY_VALUES: usize = 14;

fn energies_vec(e: &Energies) -> [f64; N_ENERGY_VALUES] {
    let a = e.accumulated;
    [
        e.kinetic,
        e.internal,
        e.damping,
        e.contact,
        e.external,
        e.input,
        e.boundary,
        e.initial_kinetic,
        a[0],
        a[1],
        a[2],
        a[3],
        a[4],
        a[5],
    ]
}

/// Serialise the simulation's state into `w`. Only a state on the step grid (every step
/// so far a full step Δt, [`Simulation::on_grid`]) can be written: a run resumed from it
/// continues with full steps, as the run that wrote it.
pub fn write_checkpoint(w: &mut impl Write, sim: &Simulation) -> std::io::Result<()> {
    if !sim.on_grid() {
        return Err(std::io::Error::other(format!(
            "no checkpoint after a shortened step (step {}, t = {:e} s is off the step grid)",
            sim.step, sim.time
        )));
    }
    {
        w.write_all(MAGIC)?;
        w.write_all(&(sim.u.len() as u64).to_le_bytes())?;
        w.write_all(&(sim.model.groups.len() as u64).to_le_bytes())?;
        w.write_all(&sim.step.to_le_bytes())?;
        put_f64s(w, &[sim.time, sim.dt])?;
        put_f64s(w, &energies_vec(&sim.energies))?;
        for field in [&sim.u, &sim.v, &sim.a] {
            for x in field.iter() {
                put_f64s(w, x)?;
            }
        }
        for g in &sim.model.groups {
            let s = g.states().current();
            w.write_all(&(s.len() as u64).to_le_bytes())?;
            put_f64s(w, s)?;
        }
        let contact = sim
            .model
            .contact
            .as_ref()
            .map(|c| c.state_values())
            .unwrap_or_default();
        w.write_all(&(contact.len() as u64).to_le_bytes())?;
        put_f64s(w, &contact)?;
        let boundary = sim
            .model
            .boundaries
            .as_ref()
            .map(|b| b.state_values())
            .unwrap_or_default();
        w.write_all(&(boundary.len() as u64).to_le_bytes())?;
        put_f64s(w, &boundary)?;
        let anchors = sim
            .model
            .anchors
            .as_ref()
            .map(|a| a.state())
            .unwrap_or_default();
        w.write_all(&(anchors.len() as u64).to_le_bytes())?;
        put_f64s(w, &anchors)?;
        Ok(())
    }
}

struct Reader<'a> {
    bytes: &'a [u8],
    pos: usize,
    file: String,
}

impl Reader<'_> {
    fn take(&mut self, n: usize) -> Result<&[u8]> {
        if self.pos + n > self.bytes.len() {
            return Err(DcfmError::Parse {
                file: self.file.clone(),
                message: format!("checkpoint truncated at byte {}", self.pos),
            });
        }
        let s = &self.bytes[self.pos..self.pos + n];
        self.pos += n;
        Ok(s)
    }
    fn u64(&mut self) -> Result<u64> {
        Ok(u64::from_le_bytes(
            self.take(8)?.try_into().expect("8 bytes"),
        ))
    }
    fn f64(&mut self) -> Result<f64> {
        Ok(f64::from_le_bytes(
            self.take(8)?.try_into().expect("8 bytes"),
        ))
    }
}

/// Restore a checkpoint's `bytes` into `sim`, which must have been built from the same
/// case; `file` names the checkpoint in errors.
pub fn read_checkpoint(bytes: &[u8], file: &str, sim: &mut Simulation) -> Result<()> {
    let file = file.to_string();
    let mut r = Reader {
        bytes,
        pos: 0,
        file: file.clone(),
    };
    let mismatch = |what: &str, found: u64, expected: usize| DcfmError::Parse {
        file: file.clone(),
        message: format!(
            "checkpoint has {found} {what}, the case has {expected}: it belongs to another case"
        ),
    };
    let magic = r.take(8)?;
    if magic != MAGIC {
        return Err(DcfmError::Parse {
            file,
            message: "no dynamic state block where the checkpoint should hold one".into(),
        });
    }
    let n = r.u64()?;
    if n as usize != sim.u.len() {
        return Err(mismatch("nodes", n, sim.u.len()));
    }
    let ng = r.u64()?;
    if ng as usize != sim.model.groups.len() {
        return Err(mismatch("element groups", ng, sim.model.groups.len()));
    }
    let step = r.u64()?;
    let time = r.f64()?;
    let dt = r.f64()?;
    if (dt - sim.dt).abs() > 1e-15 * sim.dt {
        return Err(DcfmError::Parse {
            file,
            message: format!(
                "checkpoint time step {dt:e} s differs from the case's {:e} s",
                sim.dt
            ),
        });
    }
    let e: Vec<f64> = (0..N_ENERGY_VALUES)
        .map(|_| r.f64())
        .collect::<Result<_>>()?;
    for field in [&mut sim.u, &mut sim.v, &mut sim.a] {
        for x in field.iter_mut() {
            for c in x.iter_mut() {
                *c = r.f64()?;
            }
        }
    }
    for g in sim.model.groups.iter_mut() {
        let len = r.u64()?;
        if len as usize != g.states().current().len() {
            return Err(mismatch(
                "state values in a group",
                len,
                g.states().current().len(),
            ));
        }
        let values: Vec<f64> = (0..len).map(|_| r.f64()).collect::<Result<_>>()?;
        g.restore_states(&values);
    }
    let nc = r.u64()? as usize;
    let contact: Vec<f64> = (0..nc).map(|_| r.f64()).collect::<Result<_>>()?;
    match sim.model.contact.as_mut() {
        Some(c) => c
            .restore_state(&contact)
            .map_err(|message| DcfmError::Parse {
                file: file.clone(),
                message,
            })?,
        None if nc > 0 => {
            return Err(DcfmError::Parse {
                file,
                message: "checkpoint has contact state but the case has no interface".into(),
            })
        }
        None => {}
    }
    let nb = r.u64()? as usize;
    let boundary: Vec<f64> = (0..nb).map(|_| r.f64()).collect::<Result<_>>()?;
    match sim.model.boundaries.as_mut() {
        Some(b) => b
            .restore_state(&boundary)
            .map_err(|message| DcfmError::Parse {
                file: file.clone(),
                message,
            })?,
        None if nb > 0 => {
            return Err(DcfmError::Parse {
                file,
                message: "checkpoint has boundary state but the case has no absorbing boundary"
                    .into(),
            })
        }
        None => {}
    }
    let na = r.u64()? as usize;
    let anchors: Vec<f64> = (0..na).map(|_| r.f64()).collect::<Result<_>>()?;
    let has_anchors = sim.model.anchors.is_some();
    let restored = match sim.model.anchors.as_mut() {
        Some(a) => a.restore_state(&anchors),
        None => na == 0,
    };
    if !restored {
        let message = if has_anchors {
            format!(
                "checkpoint has {na} anchor bar state values, the case's bars another number: \
                 it belongs to another case"
            )
        } else {
            "checkpoint has anchor bar state but the case has no anchors".into()
        };
        return Err(DcfmError::Parse { file, message });
    }
    sim.step = step;
    sim.time = time;
    sim.energies = Energies {
        kinetic: e[0],
        internal: e[1],
        damping: e[2],
        contact: e[3],
        external: e[4],
        input: e[5],
        boundary: e[6],
        initial_kinetic: e[7],
        accumulated: [e[8], e[9], e[10], e[11], e[12], e[13]],
    };
    sim.restored_on_grid();
    Ok(())
}

// ---- Static stage block (owner: static stage; docs/static_stage.md) -----------------------
// A checkpoint of a case with a `[static]` section starts with the static block (magic
// DCFMSTA1): the post-static configuration (active elements, initial strains, references)
// and the StaticResult, written by `write_static_block` just before `write_checkpoint`'s
// bytes. On resume, `read_static_block` (on a model freshly built from the case) rebuilds
// that configuration and returns the result and the offset where this file's dynamic block
// begins; a checkpoint without it (no static stage) reads as (None, 0).
pub use crate::stage::static_stage::checkpoint::{read_static_block, write_static_block};
