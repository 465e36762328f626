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

/// Each size's network as NeuralFoil's package ships it: layers, and the width of the hidden
/// ones (a file renamed to another size is told by its shape).
const SHAPES: [(&str, usize, usize); 7] = [
    ("xxsmall", 3, 48),
    ("xsmall", 4, 48),
    ("small", 4, 64),
    ("medium", 5, 64),
    ("large", 5, 128),
    ("xlarge", 6, 128),
    ("xxlarge", 6, 256),
];

/// The largest weights file read [bytes]: the package's largest network is 1.2 MB; a bigger
/// file is not NeuralFoil's and is refused before it is read.
pub const MAX_FILE_BYTES: u64 = 16 << 20;

/// The size used when none is asked for (NeuralFoil's own default).
pub const DEFAULT_SIZE: &str = "xlarge";

/// The environment variable naming a folder of NeuralFoil weights to use instead of the
/// built-in ones.
pub const WEIGHTS_ENV: &str = "PROPBET_NEURALFOIL_WEIGHTS";

/// The package's weights, built in (`weights/PROVENANCE.md`).
const BUILT_IN: [(&str, &[u8]); 7] = [
    ("xxsmall", include_bytes!("../weights/nn-xxsmall.npz")),
    ("xsmall", include_bytes!("../weights/nn-xsmall.npz")),
    ("small", include_bytes!("../weights/nn-small.npz")),
    ("medium", include_bytes!("../weights/nn-medium.npz")),
    ("large", include_bytes!("../weights/nn-large.npz")),
    ("xlarge", include_bytes!("../weights/nn-xlarge.npz")),
    ("xxlarge", include_bytes!("../weights/nn-xxlarge.npz")),
];
/// The inputs' scaling of the training data.
const STATS: &[u8] = include_bytes!("../weights/scaled_input_distribution.npz");

/// Inputs of the networks.
const N_INPUTS: usize = 25;
/// Batches of at least this many columns (cases and their mirror images) are split between
/// two threads.
const PARALLEL_COLUMNS: usize = 32;
/// The outputs used: confidence, CL, CD, CM and the two transition points.
const N_OUTPUTS: usize = 6;

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
#[derive(Debug, Clone, PartialEq)]
struct Layer {
    weights: nalgebra::DMatrix<f32>,
    biases: nalgebra::DVector<f32>,
}

/// One of NeuralFoil's networks with its training inputs' statistics.
#[derive(Debug, Clone)]
pub struct Network {
    /// Layers in order.
    layers: Vec<Layer>,
    /// Mean of the scaled training inputs.
    mean: nalgebra::DVector<f64>,
    /// Inverse covariance of the scaled training inputs.
    inv_cov: nalgebra::DMatrix<f64>,
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
            if w.iter().chain(b.iter()).any(|x| !x.is_finite()) {
                return Err(WeightsError::Format {
                    name: net_name.into(),
                    reason: format!("layer {i} holds a weight or bias that is not a finite number (NaN or infinite)"),
                });
            }
            width = w.nrows();
            let rows: Vec<f32> = w.iter().copied().collect();
            layers.push(Layer {
                weights: nalgebra::DMatrix::from_row_slice(w.nrows(), w.ncols(), &rows),
                biases: nalgebra::DVector::from_iterator(b.len(), b.iter().copied()),
            });
        }
        if width < N_OUTPUTS {
            return Err(WeightsError::Format {
                name: net_name.into(),
                reason: format!("the last layer has {width} outputs, fewer than the {N_OUTPUTS} coefficients"),
            });
        }
        // Only the coefficients are used: the last layer's other rows (the boundary layer's
        // data along the chord) are not computed.
        if let Some(last) = layers.last_mut() {
            last.weights = last.weights.rows(0, N_OUTPUTS).into_owned();
            last.biases = last.biases.rows(0, N_OUTPUTS).into_owned();
        }
        let mut st = open(stats_name, std::io::Cursor::new(stats))?;
        let mean: Array1<f32> = array(&mut st, stats_name, "mean_inputs_scaled")?;
        let inv_cov: Array2<f64> = array(&mut st, stats_name, "inv_cov_inputs_scaled")?;
        if mean.iter().any(|x| !x.is_finite()) || inv_cov.iter().any(|x| !x.is_finite()) {
            return Err(WeightsError::Format {
                name: stats_name.into(),
                reason: "its statistics hold a value that is not a finite number".into(),
            });
        }
        if mean.len() != N_INPUTS || inv_cov.dim() != (N_INPUTS, N_INPUTS) {
            return Err(WeightsError::Format {
                name: stats_name.into(),
                reason: format!("statistics of {} inputs, not {N_INPUTS}", mean.len()),
            });
        }
        Ok(Network {
            layers,
            mean: nalgebra::DVector::from_iterator(N_INPUTS, f64s(mean)),
            inv_cov: nalgebra::DMatrix::from_fn(N_INPUTS, N_INPUTS, |i, l| inv_cov[[i, l]]),
        })
    }

    /// The network of `size` from the folder `dir` (`nn-<size>.npz` and
    /// `scaled_input_distribution.npz`).
    pub fn load(dir: &Path, size: &str) -> Result<Network, WeightsError> {
        if !SIZES.contains(&size) {
            return Err(WeightsError::Size(size.into()));
        }
        let read = |p: &Path| {
            use std::io::Read as _;
            let error = |reason: String| WeightsError::Read {
                name: p.display().to_string(),
                reason,
            };
            let file = std::fs::File::open(p).map_err(|e| error(e.to_string()))?;
            let len = file.metadata().map_err(|e| error(e.to_string()))?.len();
            if len > MAX_FILE_BYTES {
                return Err(error(format!(
                    "{len} bytes, more than any of NeuralFoil's networks ({} MB at most): not its weights",
                    MAX_FILE_BYTES >> 20
                )));
            }
            let mut bytes = Vec::with_capacity(len as usize);
            file.take(MAX_FILE_BYTES + 1)
                .read_to_end(&mut bytes)
                .map_err(|e| error(e.to_string()))?;
            if bytes.len() as u64 > MAX_FILE_BYTES {
                return Err(error("it grew past the largest network's size while read".into()));
            }
            Ok(bytes)
        };
        let net = dir.join(format!("nn-{size}.npz"));
        let stats = dir.join("scaled_input_distribution.npz");
        let name = net.display().to_string();
        let network = Network::from_bytes(&name, &read(&net)?, &stats.display().to_string(), &read(&stats)?)?;
        network.check_shape(&name, size)?;
        Ok(network)
    }

    /// The network is of `size`'s shape (its layers and hidden width), else an error naming
    /// the size it has.
    fn check_shape(&self, name: &str, size: &str) -> Result<(), WeightsError> {
        let shape = (self.layers.len(), self.layers[0].weights.nrows());
        let Some(&(_, layers, width)) = SHAPES.iter().find(|s| s.0 == size) else {
            return Err(WeightsError::Size(size.into()));
        };
        if shape == (layers, width) {
            return Ok(());
        }
        let is = SHAPES.iter().find(|s| (s.1, s.2) == shape).map_or_else(
            || "no size NeuralFoil ships".to_string(),
            |s| format!("NeuralFoil's `{}`", s.0),
        );
        Err(WeightsError::Format {
            name: name.into(),
            reason: format!(
                "named `{size}` ({layers} layers {width} wide), but its network has {} layers {} wide: {is}",
                shape.0, shape.1
            ),
        })
    }

    /// The network of `size`: from the folder `$PROPBET_NEURALFOIL_WEIGHTS` names when it is
    /// set (the package's files of another version, say), else the weights built into propbet
    /// (this crate's `weights/`, included at compile time, so a copied binary has them).
    pub fn shipped(size: &str) -> Result<Network, WeightsError> {
        match std::env::var_os(WEIGHTS_ENV) {
            Some(dir) => Network::load(Path::new(&dir), size),
            None => Network::built_in(size),
        }
    }

    /// The network of `size` from the weights built into propbet.
    pub fn built_in(size: &str) -> Result<Network, WeightsError> {
        let net = BUILT_IN
            .iter()
            .find(|(s, _)| *s == size)
            .ok_or_else(|| WeightsError::Size(size.into()))?;
        Network::from_bytes(
            &format!("nn-{size}.npz (built into propbet)"),
            net.1,
            "scaled_input_distribution.npz (built into propbet)",
            STATS,
        )
    }

    /// The layers on a block of scaled inputs (one column per case), in single precision as
    /// the weights are stored: the networks' own precision, twice the speed of double
    /// (differences from the package's double-precision evaluation are below 1e-5 in CL and
    /// ln CD: the parity test).
    fn layers(&self, x: nalgebra::DMatrixView<'_, f64>) -> nalgebra::DMatrix<f32> {
        let last = self.layers.len() - 1;
        let mut v: nalgebra::DMatrix<f32> = x.map(|a| a as f32);
        for (k, layer) in self.layers.iter().enumerate() {
            let mut next = &layer.weights * &v;
            for mut col in next.column_iter_mut() {
                col += &layer.biases;
            }
            if k != last {
                // Swish: x sigmoid(x).
                next.apply(|y| *y /= 1.0 + fast_exp(-*y));
            }
            v = next;
        }
        v
    }

    /// The raw network on a batch (one column per case): scaled inputs to scaled outputs, each
    /// case's confidence logit lowered by its inputs' squared Mahalanobis distance over twice the
    /// input count.
    fn raw(&self, x: &nalgebra::DMatrix<f64>) -> nalgebra::DMatrix<f64> {
        let n = x.ncols();
        // A large batch is split between two threads, half the columns each (as numpy's BLAS
        // would share the package's products between the cores).
        let v = if n >= PARALLEL_COLUMNS {
            let h = n / 2;
            let (a, b) = rayon::join(|| self.layers(x.columns(0, h)), || self.layers(x.columns(h, n - h)));
            let mut v = nalgebra::DMatrix::<f32>::zeros(a.nrows(), n);
            v.columns_mut(0, h).copy_from(&a);
            v.columns_mut(h, n - h).copy_from(&b);
            v
        } else {
            self.layers(x.columns(0, n))
        };
        let mut v: nalgebra::DMatrix<f64> = v.map(f64::from);
        // Squared Mahalanobis distances d' S^-1 d of every column at once.
        let mut d = x.clone();
        for mut col in d.column_iter_mut() {
            col -= &self.mean;
        }
        let sd = &self.inv_cov * &d;
        for j in 0..x.ncols() {
            let m2 = d.column(j).dot(&sd.column(j));
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

/// e^x in single precision, within 2e-7 relative of `f32::exp` (the test) and branch-free, so
/// that a layer's activations vectorise (the library's `expf` was a quarter of the time).
/// Written here because no well-kept crate offers a vectorisable `exp` for `f32` slices: the
/// classic reduction x = n ln 2 + r, |r| <= ln 2 / 2, e^r by its Taylor polynomial to r^7,
/// 2^n put into the exponent bits.
#[inline]
fn fast_exp(x: f32) -> f32 {
    // 1.5 2^23: adding it rounds to an integer held in the low bits of the sum's mantissa
    // (no float-to-integer conversion, which does not vectorise).
    const SHIFT: f32 = 12_582_912.0;
    let x = x.clamp(-87.0, 88.0);
    let t = x * std::f32::consts::LOG2_E + SHIFT;
    let n = t - SHIFT;
    // ln 2 in two parts, the first exact in f32, so that r keeps its precision.
    let r = x - n * 0.693_145_75 - n * 1.428_606_8e-6;
    let p = 1.0
        + r * (1.0
            + r * (0.5
                + r * (1.0 / 6.0 + r * (1.0 / 24.0 + r * (1.0 / 120.0 + r * (1.0 / 720.0 + r * (1.0 / 5040.0)))))));
    p * f32::from_bits(t.to_bits().wrapping_sub(SHIFT.to_bits()).wrapping_add(127) << 23)
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
            let n = Network::built_in(s).unwrap();
            assert!(n.layers.len() >= 2, "{s}");
            // The built-in weights are the files in weights/.
            let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("weights");
            let from_files = Network::load(&dir, s).unwrap();
            assert_eq!(from_files.layers, n.layers, "{s}");
        }
        assert_eq!(BUILT_IN.map(|b| b.0), SIZES);
        let e = Network::load(Path::new("/nowhere"), "xlarge").unwrap_err().to_string();
        assert!(e.contains("/nowhere/nn-xlarge.npz") && e.contains("cannot read"), "{e}");
        let e = Network::from_bytes("x.npz", b"not a zip", "s.npz", b"")
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("x.npz: not NeuralFoil's weights"), "{e}");
        assert!(matches!(Network::built_in("huge"), Err(WeightsError::Size(_))));
        assert!((ln_eps() + 707.48).abs() < 0.01);
    }

    /// A weights folder whose files are not what they claim: a renamed size, a NaN, a file of
    /// 4 GB (sparse: nothing is written), each refused naming the file.
    #[test]
    fn weights_that_are_not_what_they_claim_are_refused() {
        let shipped = Path::new(env!("CARGO_MANIFEST_DIR")).join("weights");
        let dir = tempfile::tempdir().unwrap();
        let stats = "scaled_input_distribution.npz";
        std::fs::copy(shipped.join(stats), dir.path().join(stats)).unwrap();
        std::fs::copy(shipped.join("nn-xxsmall.npz"), dir.path().join("nn-xlarge.npz")).unwrap();
        let e = Network::load(dir.path(), "xlarge").unwrap_err().to_string();
        assert!(
            e.contains("named `xlarge`") && e.contains("NeuralFoil's `xxsmall`"),
            "{e}"
        );
        // One weight NaN.
        let mut npz = NpzReader::new(std::fs::File::open(shipped.join("nn-small.npz")).unwrap()).unwrap();
        let names = npz.names().unwrap();
        let mut out = ndarray_npy::NpzWriter::new(std::fs::File::create(dir.path().join("nn-small.npz")).unwrap());
        for n in names {
            let key = n.trim_end_matches(".npy");
            if key.ends_with("weight") {
                let mut w: Array2<f32> = npz.by_name(&n).unwrap();
                if key == "net.2.weight" {
                    w[[1, 1]] = f32::NAN;
                }
                out.add_array(key, &w).unwrap();
            } else {
                let b: Array1<f32> = npz.by_name(&n).unwrap();
                out.add_array(key, &b).unwrap();
            }
        }
        out.finish().unwrap();
        let e = Network::load(dir.path(), "small").unwrap_err().to_string();
        assert!(
            e.contains("nn-small.npz") && e.contains("layer 2 holds a weight or bias that is not a finite"),
            "{e}"
        );
        let huge = std::fs::File::create(dir.path().join("nn-medium.npz")).unwrap();
        huge.set_len(4 << 30).unwrap();
        let e = Network::load(dir.path(), "medium").unwrap_err().to_string();
        assert!(
            e.contains("nn-medium.npz") && e.contains("4294967296 bytes, more than any"),
            "{e}"
        );
    }

    #[test]
    fn the_fast_exponential_is_the_librarys() {
        let mut worst = 0.0f32;
        for i in -87_000..=88_000 {
            let x = i as f32 / 1000.0;
            worst = worst.max((fast_exp(x) / x.exp() - 1.0).abs());
        }
        assert!(worst < 2e-7, "{worst}");
        assert_eq!(fast_exp(-200.0), fast_exp(-87.0), "clamped, not a wrapped exponent");
        assert!(fast_exp(200.0).is_finite());
    }
}
