//! Lee–Fenves plastic-damage model (placeholder API while the model is written in its own
//! branch; replaced before landing).

use crate::material::{Elastic, PointContext, Voigt};

#[derive(Clone, Debug, serde::Deserialize, PartialEq)]
pub struct PlasticDamageParams {}

#[derive(Clone, Debug)]
pub struct PlasticDamage {
    elastic: Elastic,
}

impl PlasticDamage {
    pub fn new(_n: &str, elastic: Elastic, _p: &PlasticDamageParams) -> crate::Result<Self> {
        Ok(Self { elastic })
    }
    pub fn max_element_size(&self) -> f64 {
        f64::INFINITY
    }
    pub fn elastic(&self) -> &Elastic {
        &self.elastic
    }
    pub fn state_len(&self) -> usize {
        0
    }
    pub fn init_state(&self, _s: &mut [f64]) {}
    pub fn update(
        &self,
        strain: &Voigt,
        _old: &[f64],
        _new: &mut [f64],
        _ctx: &PointContext,
    ) -> Voigt {
        self.elastic.stress(strain)
    }
    pub fn stress_from_state(&self, strain: &Voigt, _s: &[f64]) -> Voigt {
        self.elastic.stress(strain)
    }
    pub fn damage(&self, _s: &[f64]) -> f64 {
        0.0
    }
}
