//! The scan's settings as a user writes them (`propbet scan`'s flags, a case's `[geometry]`
//! keys: one struct, read by both) and the geometry pipeline's options they make.

use serde::Deserialize;

use nalgebra::Vector3;
use propbet_geometry::cloud::parse_colour;
use propbet_geometry::scan::{default_stations, BoxSpec, Manual, ScanOptions, SectionKind};

use crate::values::{parse_length_unit, parse_list};
use crate::{Error, Result};

/// Slab thickness of a cloud's sections when none is given [mm].
pub const DEFAULT_SLAB_MM: f64 = 0.25;
/// Points per blade a sparse cloud's slab is widened to when none is given.
pub const DEFAULT_SLAB_POINTS: usize = 400;
/// The reference box's centre in the propeller frame when none is given [mm].
pub const DEFAULT_BOX_OFFSET: &str = "0,0,-40";
/// The reference box's face colours when none are given.
pub const DEFAULT_BOX_COLOUR: &str = "grey,blue";
/// Statistical outlier removal when none is given: neighbours, sigmas.
pub const DEFAULT_OUTLIERS: &str = "8,2.5";
/// Manual alignment's rotations when none are given [deg].
pub const DEFAULT_ROTATE: &str = "0,0,0";

/// The scan's settings, as text where the flag takes text. Every field is a flag of
/// `propbet scan` (`box_dims` is `--box`) and a key of a case's `[geometry]` (`box`): the
/// binary parses its flags into this struct, a case file deserializes into it.
#[derive(Debug, Clone, Default, PartialEq, Deserialize, clap::Args)]
#[serde(deny_unknown_fields)]
pub struct ScanSettings {
    /// Length unit of the file (m, cm, mm, in; None: mm, assumed).
    #[arg(long = crate::UNITS.flag, help = crate::UNITS.help)]
    pub units: Option<String>,
    /// Stations as r/R (None: [`default_stations`]).
    #[arg(long = crate::STATIONS.flag, help = crate::STATIONS.help)]
    pub stations: Option<String>,
    /// Planar sections (the plane x = r across the blade) instead of cylindrical (r = const).
    #[serde(default)]
    #[arg(long)]
    pub planar: bool,
    /// Slab thickness of a cloud's sections [mm] (None: [`DEFAULT_SLAB_MM`]).
    #[arg(long, help = format!("Slab thickness of a cloud's sections [mm] [default: {DEFAULT_SLAB_MM}]"))]
    pub slab: Option<f64>,
    /// Points per blade a sparse cloud's slab is widened to (0: keep the slab; None:
    /// [`DEFAULT_SLAB_POINTS`]).
    #[arg(long, help = format!("Widen a sparse cloud's slab (up to 4 times) until a section holds this many points \
        per blade (0: keep the slab as given) [default: {DEFAULT_SLAB_POINTS}]"))]
    pub slab_points: Option<usize>,
    /// Blade colours to keep (clouds): names (orange, black, ...), #rrggbb or r/g/b, comma-separated.
    #[arg(long)]
    pub blade_colour: Option<String>,
    /// Colour-distance threshold (default: Otsu's suggestion from the histogram).
    #[arg(long)]
    pub colour_threshold: Option<f64>,
    /// Reference box edge lengths along the propeller's x, y, z [mm]: 50.8x48.26x50.8.
    #[serde(rename = "box")]
    #[arg(long = "box")]
    pub box_dims: Option<String>,
    /// The box centre in the propeller frame [mm]: x,y,z (the box is fixed to the hub).
    #[arg(long, default_value = DEFAULT_BOX_OFFSET, allow_hyphen_values = true)]
    pub box_offset: Option<String>,
    /// Colours of the box faces.
    #[arg(long, default_value = DEFAULT_BOX_COLOUR)]
    pub box_colour: Option<String>,
    /// One point on each visible box face (file units), `x,y,z;x,y,z;...`, instead of finding
    /// the faces automatically.
    #[arg(long, allow_hyphen_values = true)]
    pub box_seeds: Option<String>,
    /// Region of interest in file units: xmin,ymin,zmin,xmax,ymax,zmax.
    #[arg(long, allow_hyphen_values = true)]
    pub crop: Option<String>,
    /// Statistical outlier removal for clouds: neighbours,sigmas, or `off`.
    #[arg(long, default_value = DEFAULT_OUTLIERS)]
    pub outliers: Option<String>,
    /// Manual alignment: a point at the root of blade 0 (file units) x,y,z.
    #[arg(long, allow_hyphen_values = true, requires = "tip_point")]
    pub root_point: Option<String>,
    /// Manual alignment: a point at the tip of blade 0.
    #[arg(long, allow_hyphen_values = true, requires = "root_point")]
    pub tip_point: Option<String>,
    /// Manual alignment: the hub centre (default: the root point moved along the blade axis to
    /// the station of the scan's centroid).
    #[arg(long, allow_hyphen_values = true)]
    pub origin: Option<String>,
    /// Manual alignment: rotations about the frame's x, y, z [deg].
    #[arg(long, allow_hyphen_values = true, default_value = DEFAULT_ROTATE)]
    pub rotate: Option<String>,
    /// Manual scale from a known length: `x1,y1,z1,x2,y2,z2,L` (two points in file units and
    /// their true distance in mm).
    #[arg(long, allow_hyphen_values = true)]
    pub known_length: Option<String>,
}

fn numbers(flag: &str, text: &str, n: usize) -> Result<Vec<f64>> {
    let v: Vec<f64> = text
        .split(',')
        .map(|s| {
            s.trim()
                .parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| Error::value(flag, text, format!("'{}' is not a number", s.trim())))
        })
        .collect::<Result<_>>()?;
    if v.len() != n {
        return Err(Error::value(
            flag,
            text,
            format!("expected {n} numbers, found {}", v.len()),
        ));
    }
    Ok(v)
}

fn vec3(flag: &str, text: &str) -> Result<Vector3<f64>> {
    let v = numbers(flag, text, 3)?;
    Ok(Vector3::new(v[0], v[1], v[2]))
}

fn colours(flag: &str, text: &str) -> Result<Vec<[u8; 3]>> {
    text.split(',')
        .map(|s| parse_colour(s).map_err(|e| Error::value(flag, s, e)))
        .collect()
}

impl ScanSettings {
    /// The keys a case's `[geometry]` holds for these settings (named where a case sets a
    /// scan's settings without a scan).
    pub fn as_keys(&self) -> String {
        let mut out = Vec::new();
        let mut text = |k: &str, v: &Option<String>| {
            if let Some(v) = v {
                out.push(format!("{k} = {v:?}"));
            }
        };
        text("units", &self.units);
        text("stations", &self.stations);
        text("blade_colour", &self.blade_colour);
        text("box", &self.box_dims);
        text("box_offset", &self.box_offset);
        text("box_colour", &self.box_colour);
        text("box_seeds", &self.box_seeds);
        text("crop", &self.crop);
        text("outliers", &self.outliers);
        text("root_point", &self.root_point);
        text("tip_point", &self.tip_point);
        text("origin", &self.origin);
        text("rotate", &self.rotate);
        text("known_length", &self.known_length);
        if self.planar {
            out.push("planar = true".into());
        }
        if let Some(s) = self.slab {
            out.push(format!("slab = {s}"));
        }
        if let Some(s) = self.slab_points {
            out.push(format!("slab_points = {s}"));
        }
        if let Some(s) = self.colour_threshold {
            out.push(format!("colour_threshold = {s}"));
        }
        out.join(", ")
    }

    /// The geometry pipeline's options (lengths in metres; the stations and the slab are
    /// checked by the scan stage).
    pub fn options(&self) -> Result<ScanOptions> {
        // Metres per file unit.
        let units = parse_length_unit(self.units.as_deref().unwrap_or("mm"))?;
        let stations = match &self.stations {
            Some(s) => parse_list("--stations", s)?,
            None => default_stations(),
        };
        let mut scale = units;
        if let Some(k) = &self.known_length {
            let v = numbers("--known-length", k, 7)?;
            let d = (Vector3::new(v[0], v[1], v[2]) - Vector3::new(v[3], v[4], v[5])).norm();
            if d <= 0.0 || v[6] <= 0.0 {
                return Err(Error::value(
                    "--known-length",
                    k,
                    "two distinct points and a positive length are needed",
                ));
            }
            scale = v[6] / d / 1000.0;
        }
        Ok(ScanOptions {
            scale,
            scale_given: self.units.is_some() || self.known_length.is_some(),
            stations,
            kind: if self.planar {
                SectionKind::Planar
            } else {
                SectionKind::Cylindrical
            },
            slab: self.slab.unwrap_or(DEFAULT_SLAB_MM) / 1000.0,
            slab_points: self.slab_points.unwrap_or(DEFAULT_SLAB_POINTS),
            blade_colours: self
                .blade_colour
                .as_deref()
                .map(|c| colours("--blade-colour", c))
                .transpose()?
                .unwrap_or_default(),
            colour_threshold: self.colour_threshold,
            reference_box: self.reference_box()?,
            crop: match &self.crop {
                None => None,
                Some(c) => {
                    let v = numbers("--crop", c, 6)?;
                    Some((Vector3::new(v[0], v[1], v[2]), Vector3::new(v[3], v[4], v[5])))
                }
            },
            outliers: self.outliers()?,
            manual: self.manual(scale)?,
        })
    }

    fn reference_box(&self) -> Result<Option<BoxSpec>> {
        let Some(d) = &self.box_dims else { return Ok(None) };
        let v: Vec<f64> = d
            .split(['x', 'X', ','])
            .map(|s| s.trim().parse::<f64>().ok().filter(|x| *x > 0.0))
            .collect::<Option<_>>()
            .ok_or_else(|| Error::value("--box", d, "expected three positive lengths, e.g. 50.8x48.26x50.8"))?;
        if v.len() != 3 {
            return Err(Error::value("--box", d, "expected three lengths, e.g. 50.8x48.26x50.8"));
        }
        let o = vec3("--box-offset", self.box_offset.as_deref().unwrap_or(DEFAULT_BOX_OFFSET))?;
        Ok(Some(BoxSpec {
            dims: [v[0] / 1000.0, v[1] / 1000.0, v[2] / 1000.0],
            offset: [o.x / 1000.0, o.y / 1000.0, o.z / 1000.0],
            colours: colours("--box-colour", self.box_colour.as_deref().unwrap_or(DEFAULT_BOX_COLOUR))?,
            seeds: match &self.box_seeds {
                None => Vec::new(),
                Some(t) => t.split(';').map(|p| vec3("--box-seeds", p)).collect::<Result<_>>()?,
            },
        }))
    }

    fn outliers(&self) -> Result<Option<(usize, f64)>> {
        let text = self.outliers.as_deref().unwrap_or(DEFAULT_OUTLIERS);
        if text == "off" {
            return Ok(None);
        }
        let v = numbers("--outliers", text, 2)?;
        if v[0] < 1.0 || v[1] <= 0.0 {
            return Err(Error::value(
                "--outliers",
                text,
                "neighbours >= 1 and sigmas > 0, or 'off'",
            ));
        }
        Ok(Some((v[0] as usize, v[1])))
    }

    fn manual(&self, scale: f64) -> Result<Option<Manual>> {
        match (&self.root_point, &self.tip_point) {
            (Some(r), Some(t)) => {
                let rot = vec3("--rotate", self.rotate.as_deref().unwrap_or(DEFAULT_ROTATE))?;
                Ok(Some(Manual {
                    root: vec3("--root-point", r)?,
                    tip: vec3("--tip-point", t)?,
                    origin: self.origin.as_deref().map(|o| vec3("--origin", o)).transpose()?,
                    rotate: [rot.x.to_radians(), rot.y.to_radians(), rot.z.to_radians()],
                    scale,
                }))
            }
            (None, None) => Ok(None),
            _ => Err(Error::Conflict(
                "--root-point and --tip-point: manual alignment needs both".into(),
            )),
        }
    }
}
