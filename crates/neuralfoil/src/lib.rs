//! NeuralFoil's networks evaluated in Rust: a section's lift, drag and moment coefficients,
//! transition points and the network's confidence in its own answer, from the section's
//! Kulfan (CST) shape, the angle of attack, the Reynolds number, Ncrit and forced transition.
//!
//! The networks are NeuralFoil 0.3.3's (Peter Sharpe, MIT; `weights/PROVENANCE.md`): plain
//! multilayer perceptrons with swish activations, read from the package's `.npz` files with
//! `ndarray-npy`. Evaluation follows the package's `get_aero_from_kulfan_parameters`: the
//! inputs scaled as it scales them, the network evaluated on the section and on its mirror image
//! (upper and lower surfaces swapped, the angle negated) and the two answers averaged, the
//! confidence lowered by the inputs' Mahalanobis distance from the training data. No crate does
//! this; it is written here, and tested against the package itself (`tests/parity.rs`).
#![deny(missing_docs)]

use std::io::{Read, Seek};
use std::path::Path;

pub mod cst;

use ndarray::{Array1, Array2};

use ndarray_npy::NpzReader;

/// The network sizes shipped (NeuralFoil's names; `xxxlarge` is not copied).
pub const SIZES: [&str; 7] = ["xxsmall", "xsmall", "small", "medium", "large", "xlarge", "xxlarge"];

/// The size used when none is asked for (NeuralFoil's own default).
pub const DEFAULT_SIZE: &str = "xlarge";

/// Inputs of the networks.
const N_INPUTS: usize = 25;

/// A weights file that cannot be used.
#[derive(Debug, thiserror::Error)]
pub enum WeightsError {
    /// The file cannot be read.
    #[error("{name}: cannot read NeuralFoil's weights: {reason}")]
    Read {
        /// The file.
        name: String,
        /// Why.
        reason: String,
    },
    /// The file is not a set of networks NeuralFoil's code would evaluate.
    #[error("{name}: not NeuralFoil's weights: {reason}")]
    Format {
        /// The file.
        name: String,
        /// What is wrong.
        reason: String,
    },
    /// A size that is not shipped.
    #[error("NeuralFoil model size `{0}`: one of xxsmall, xsmall, small, medium, large, xlarge, xxlarge")]
    Size(String),
}

/// A section's shape as NeuralFoil takes it: Kulfan's CST with 8 weights a side, the
/// leading-edge modification and the trailing-edge thickness (all chord-normalised).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Kulfan {
    /// Upper-surface weights, leading edge to trailing edge.
    pub upper: [f64; 8],
    /// Lower-surface weights.
    pub lower: [f64; 8],
    /// Leading-edge modification weight.
    pub leading_edge: f64,
    /// Trailing-edge thickness [chord].
    pub te_thickness: f64,
}

/// One operating condition of a section.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Condition {
    /// Angle of attack [deg].
    pub alpha_deg: f64,
    /// Reynolds number.
    pub re: f64,
    /// Transition amplification ratio.
    pub ncrit: f64,
    /// Forced transition on the upper surface [x/c] (1: free).
    pub xtr_upper: f64,
    /// Forced transition on the lower surface [x/c] (1: free).
    pub xtr_lower: f64,
}

/// What the networks say of a section at a condition.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Aero {
    /// The network's confidence in this answer, 0 to 1.
    pub confidence: f64,
    /// Lift coefficient.
    pub cl: f64,
    /// Drag coefficient.
    pub cd: f64,
    /// Moment coefficient about the quarter chord.
    pub cm: f64,
    /// Transition on the upper surface [x/c].
    pub top_xtr: f64,
    /// Transition on the lower surface [x/c].
    pub bot_xtr: f64,
}

/// One layer: weights (outputs x inputs) and biases.
#[derive(Debug, Clone)]
struct Layer {
    weights: nalgebra::DMatrix<f64>,
    biases: nalgebra::DVector<f64>,
}

/// One of NeuralFoil's networks with its training inputs' statistics.
#[derive(Debug, Clone)]
pub struct Network {
    /// Layers in order.
    layers: Vec<Layer>,
    /// Mean of the scaled training inputs.
    mean: Array1<f64>,
    /// Inverse covariance of the scaled training inputs.
    inv_cov: Array2<f64>,
}

fn f64s<D: ndarray::Dimension>(a: ndarray::Array<f32, D>) -> ndarray::Array<f64, D> {
    a.mapv(f64::from)
}

fn open<R: Read + Seek>(name: &str, r: R) -> Result<NpzReader<R>, WeightsError> {
    NpzReader::new(r).map_err(|e| WeightsError::Format {
        name: name.into(),
        reason: e.to_string(),
    })
}

/// An array of a `.npz`, with or without the `.npy` suffix on its name inside.
fn array<R: Read + Seek, T: ndarray_npy::ReadableElement, D: ndarray::Dimension>(
    npz: &mut NpzReader<R>,
    file: &str,
    key: &str,
) -> Result<ndarray::Array<T, D>, WeightsError> {
    npz.by_name(key)
        .or_else(|_| npz.by_name(&format!("{key}.npy")))
        .map_err(|e| WeightsError::Format {
            name: file.into(),
            reason: format!("{key}: {e}"),
        })
}

impl Network {
    /// The networks of the files `net` (`nn-<size>.npz`) and `stats`
    /// (`scaled_input_distribution.npz`), read from their bytes; `net_name` and `stats_name`
    /// name them in errors.
    pub fn from_bytes(net_name: &str, net: &[u8], stats_name: &str, stats: &[u8]) -> Result<Network, WeightsError> {
        let mut npz = open(net_name, std::io::Cursor::new(net))?;
        let names = npz.names().map_err(|e| WeightsError::Format {
            name: net_name.into(),
            reason: e.to_string(),
        })?;
        // Layers are `net.<i>.weight` and `net.<i>.bias`, in the order of i.
        let mut indices: Vec<usize> = names
            .iter()
            .filter_map(|n| {
                n.trim_end_matches(".npy")
                    .strip_prefix("net.")?
                    .strip_suffix(".weight")?
                    .parse()
                    .ok()
            })
            .collect();
        indices.sort_unstable();
        if indices.is_empty() {
            return Err(WeightsError::Format {
                name: net_name.into(),
                reason: format!("no `net.<i>.weight` arrays (it holds {})", names.join(", ")),
            });
        }
        let mut layers = Vec::new();
        let mut width = N_INPUTS;
        for i in indices {
            let w: Array2<f32> = array(&mut npz, net_name, &format!("net.{i}.weight"))?;
            let b: Array1<f32> = array(&mut npz, net_name, &format!("net.{i}.bias"))?;
            if w.ncols() != width || w.nrows() != b.len() {
                return Err(WeightsError::Format {
                    name: net_name.into(),
                    reason: format!(
                        "layer {i}: weights {}x{} and {} biases after a layer of {width}",
                        w.nrows(),
                        w.ncols(),
                        b.len()
                    ),
                });
            }
            width = w.nrows();
            let rows: Vec<f64> = w.iter().map(|&v| f64::from(v)).collect();
            layers.push(Layer {
                weights: nalgebra::DMatrix::from_row_slice(w.nrows(), w.ncols(), &rows),
                biases: nalgebra::DVector::from_iterator(b.len(), b.iter().map(|&v| f64::from(v))),
            });
        }
        if width < 6 {
            return Err(WeightsError::Format {
                name: net_name.into(),
                reason: format!("the last layer has {width} outputs, fewer than the 6 coefficients"),
            });
        }
        let mut st = open(stats_name, std::io::Cursor::new(stats))?;
        let mean: Array1<f32> = array(&mut st, stats_name, "mean_inputs_scaled")?;
        let inv_cov: Array2<f64> = array(&mut st, stats_name, "inv_cov_inputs_scaled")?;
        if mean.len() != N_INPUTS || inv_cov.dim() != (N_INPUTS, N_INPUTS) {
            return Err(WeightsError::Format {
                name: stats_name.into(),
                reason: format!("statistics of {} inputs, not {N_INPUTS}", mean.len()),
            });
        }
        Ok(Network {
            layers,
            mean: f64s(mean),
            inv_cov,
        })
    }

    /// The network of `size` from the folder `dir` (`nn-<size>.npz` and
    /// `scaled_input_distribution.npz`).
    pub fn load(dir: &Path, size: &str) -> Result<Network, WeightsError> {
        if !SIZES.contains(&size) {
            return Err(WeightsError::Size(size.into()));
        }
        let read = |p: &Path| {
            std::fs::read(p).map_err(|e| WeightsError::Read {
                name: p.display().to_string(),
                reason: e.to_string(),
            })
        };
        let net = dir.join(format!("nn-{size}.npz"));
        let stats = dir.join("scaled_input_distribution.npz");
        Network::from_bytes(
            &net.display().to_string(),
            &read(&net)?,
            &stats.display().to_string(),
            &read(&stats)?,
        )
    }

    /// The network of `size` from the weights shipped with this crate.
    pub fn shipped(size: &str) -> Result<Network, WeightsError> {
        Network::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("weights"), size)
    }

    /// The raw network on a batch (one column per case): scaled inputs to scaled outputs, each
    /// case's confidence logit lowered by its inputs' squared Mahalanobis distance over twice the
    /// input count.
    fn raw(&self, x: &nalgebra::DMatrix<f64>) -> nalgebra::DMatrix<f64> {
        let last = self.layers.len() - 1;
        let mut v = x.clone();
        for (k, layer) in self.layers.iter().enumerate() {
            let mut next = &layer.weights * &v;
            for mut col in next.column_iter_mut() {
                col += &layer.biases;
            }
            if k != last {
                // Swish: x sigmoid(x).
                next.apply(|y| *y /= 1.0 + (-*y).exp());
            }
            v = next;
        }
        for (j, col) in x.column_iter().enumerate() {
            let d: Vec<f64> = col.iter().zip(&self.mean).map(|(a, m)| a - m).collect();
            let mut m2 = 0.0;
            for i in 0..N_INPUTS {
                for l in 0..N_INPUTS {
                    m2 += d[i] * self.inv_cov[[i, l]] * d[l];
                }
            }
            v[(0, j)] -= m2 / (2.0 * N_INPUTS as f64);
        }
        v
    }

    /// The section at each condition (one batch through the network).
    pub fn evaluate_many(&self, k: &Kulfan, conditions: &[Condition]) -> Vec<Aero> {
        let n = conditions.len();
        // Columns 0..n: the section; n..2n: its mirror image (surfaces swapped and negated,
        // the angle negated, transition swapped).
        let mut x = nalgebra::DMatrix::<f64>::zeros(N_INPUTS, 2 * n);
        for (j, c) in conditions.iter().enumerate() {
            let a = c.alpha_deg.to_radians();
            let mut v = [0.0; N_INPUTS];
            v[..8].copy_from_slice(&k.upper);
            v[8..16].copy_from_slice(&k.lower);
            v[16] = k.leading_edge;
            v[17] = k.te_thickness * 50.0;
            v[18] = (2.0 * a).sin();
            v[19] = a.cos();
            v[20] = 1.0 - a.cos().powi(2);
            v[21] = (c.re.ln() - 12.5) / 3.5;
            v[22] = (c.ncrit - 9.0) / 4.5;
            v[23] = c.xtr_upper;
            v[24] = c.xtr_lower;
            let mut f = v;
            for i in 0..8 {
                f[i] = -v[8 + i];
                f[8 + i] = -v[i];
            }
            f[16] = -v[16];
            f[18] = -v[18];
            f[23] = v[24];
            f[24] = v[23];
            for i in 0..N_INPUTS {
                x[(i, j)] = v[i];
                x[(i, n + j)] = f[i];
            }
        }
        let y = self.raw(&x);
        (0..n)
            .map(|j| {
                let (a, b) = (y.column(j), y.column(n + j));
                // The mirror's outputs back: lift and moment negated, transition points swapped.
                let fused = |i: usize, back: f64| 0.5 * (a[i] + back);
                let confidence = 1.0 / (1.0 + (-fused(0, b[0]).clamp(ln_eps(), -ln_eps())).exp());
                Aero {
                    confidence,
                    cl: fused(1, -b[1]) / 2.0,
                    cd: ((fused(2, b[2]) - 2.0) * 2.0).exp(),
                    cm: fused(3, -b[3]) / 20.0,
                    top_xtr: fused(4, b[5]).clamp(0.0, 1.0),
                    bot_xtr: fused(5, b[4]).clamp(0.0, 1.0),
                }
            })
            .collect()
    }

    /// The section's coefficients at a condition.
    pub fn evaluate(&self, k: &Kulfan, c: &Condition) -> Aero {
        self.evaluate_many(k, std::slice::from_ref(c))[0]
    }

    /// A polar: the section at each angle of `alphas_deg`, the rest of the condition as `c`.
    pub fn polar(&self, k: &Kulfan, alphas_deg: &[f64], c: &Condition) -> Vec<Aero> {
        let conditions: Vec<Condition> = alphas_deg
            .iter()
            .map(|&alpha_deg| Condition { alpha_deg, ..*c })
            .collect();
        self.evaluate_many(k, &conditions)
    }
}

/// ln of the package's clipping epsilon (10 / the largest f64), which bounds the sigmoid's
/// argument.
fn ln_eps() -> f64 {
    (10.0 / f64::MAX).ln()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_shipped_size_reads_and_a_bad_file_is_named() {
        for s in SIZES {
            let n = Network::shipped(s).unwrap();
            assert!(n.layers.len() >= 2, "{s}");
        }
        let e = Network::load(Path::new("/nowhere"), "xlarge").unwrap_err().to_string();
        assert!(e.contains("/nowhere/nn-xlarge.npz") && e.contains("cannot read"), "{e}");
        let e = Network::from_bytes("x.npz", b"not a zip", "s.npz", b"")
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("x.npz: not NeuralFoil's weights"), "{e}");
        assert!(matches!(Network::shipped("huge"), Err(WeightsError::Size(_))));
        assert!((ln_eps() + 707.48).abs() < 0.01);
    }
}
