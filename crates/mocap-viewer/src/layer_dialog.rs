//! What the Layer window (Edit ▸ Layer) is set to, as plain data.

use mocap::ops::layer::{Blend, Layer};

/// What the Layer window is set to.
#[derive(Clone, Debug, PartialEq)]
pub struct LayerDialog {
    /// The base character.
    pub character: usize,
    /// The base joint whose subtree the layer drives.
    pub joint: String,
    /// The character whose clip is layered (None until one is chosen).
    pub source: Option<usize>,
    /// 0 (base only) to 1 (layer only).
    pub weight: f32,
    /// Seconds of fade in and out.
    pub fades: (f64, f64),
    /// Additive (else override).
    pub additive: bool,
    /// Explicit matches (base joint, layer joint; empty: left out).
    pub map: Vec<(String, String)>,
}

impl LayerDialog {
    /// A full-weight override layer on `joint` of `character`, names matched.
    pub fn new(character: usize, joint: &str) -> LayerDialog {
        LayerDialog {
            character,
            joint: joint.to_owned(),
            source: None,
            weight: 1.0,
            fades: (0.0, 0.0),
            additive: false,
            map: Vec::new(),
        }
    }

    /// The core layer these settings make.
    pub fn layer(&self) -> Layer {
        let blend = if self.additive { Blend::Additive } else { Blend::Override };
        Layer {
            weight: self.weight,
            fade_in: self.fades.0,
            fade_out: self.fades.1,
            blend,
            map: self.map.clone(),
            ..Layer::on(&self.joint)
        }
    }
}
