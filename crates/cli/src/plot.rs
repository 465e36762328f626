//! Figures: panels of x-y series drawn with plotters, to SVG or PNG (by the file's extension),
//! with the DejaVu Sans font compiled in (assets/fonts) so that text renders the same on every
//! machine. Files are written atomically.

use std::path::Path;
use std::sync::Once;

use anyhow::{anyhow, bail, Result};
use plotters::prelude::*;
use plotters::style::{register_font, FontStyle};

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mark {
    /// Connected line.
    Line,
    /// Separate dots.
    Dots,
}

/// One named series.
#[derive(Debug, Clone)]
pub struct Series {
    /// Legend text.
    pub name: String,
    /// Points (x, y); non-finite ones are skipped.
    pub points: Vec<(f64, f64)>,
    /// Line or dots.
    pub mark: Mark,
    /// Palette index (default: the series' position), so that related series share a colour.
    pub colour: Option<usize>,
}

/// One chart of a figure.
#[derive(Debug, Clone)]
pub struct Panel {
    /// Caption.
    pub title: String,
    /// X axis label.
    pub x_label: String,
    /// Y axis label.
    pub y_label: String,
    /// The data.
    pub series: Vec<Series>,
}

static FONT: Once = Once::new();
const FONT_BYTES: &[u8] = include_bytes!("../../../assets/fonts/DejaVuSans.ttf");

fn register() {
    FONT.call_once(|| {
        // The font is compiled in; registering it cannot meet a missing file.
        let _ = register_font("sans-serif", FontStyle::Normal, FONT_BYTES);
    });
}

/// Colour of the i-th series (a colour-blind-safe palette, Okabe-Ito).
fn colour(i: usize) -> RGBColor {
    const P: [(u8, u8, u8); 7] = [
        (0, 114, 178),
        (213, 94, 0),
        (0, 158, 115),
        (204, 121, 167),
        (230, 159, 0),
        (86, 180, 233),
        (0, 0, 0),
    ];
    let (r, g, b) = P[i % P.len()];
    RGBColor(r, g, b)
}

/// Draws `panels` side by side into `path` (.svg or .png), `width` x `height` pixels.
pub fn draw(path: &Path, panels: &[Panel], width: u32, height: u32, inputs: &[&Path]) -> Result<()> {
    register();
    let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("svg") => {
            let mut text = String::new();
            {
                let root = SVGBackend::with_string(&mut text, (width, height)).into_drawing_area();
                render(&root, panels)?;
                root.present().map_err(|e| anyhow!("{}: {e}", path.display()))?;
            }
            crate::output::write_atomic(path, &[text.as_bytes()], inputs)
        }
        Some("png") => {
            let mut rgb = vec![255u8; (width * height * 3) as usize];
            {
                let root = BitMapBackend::with_buffer(&mut rgb, (width, height)).into_drawing_area();
                render(&root, panels)?;
                root.present().map_err(|e| anyhow!("{}: {e}", path.display()))?;
            }
            let png = encode_png(&rgb, width, height)?;
            crate::output::write_atomic(path, &[png.as_slice()], inputs)
        }
        _ => bail!("{}: plots are written as .svg or .png", path.display()),
    }
}

fn render<DB: DrawingBackend>(root: &DrawingArea<DB, plotters::coord::Shift>, panels: &[Panel]) -> Result<()>
where
    DB::ErrorType: 'static,
{
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| anyhow!("plot: {e:?}");
    root.fill(&WHITE).map_err(err)?;
    let areas = root.split_evenly((1, panels.len().max(1)));
    for (panel, area) in panels.iter().zip(areas.iter()) {
        let pts = panel
            .series
            .iter()
            .flat_map(|s| s.points.iter())
            .filter(|p| p.0.is_finite() && p.1.is_finite());
        let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY);
        for p in pts {
            x0 = x0.min(p.0);
            x1 = x1.max(p.0);
            y0 = y0.min(p.1);
            y1 = y1.max(p.1);
        }
        if !x0.is_finite() {
            (x0, x1, y0, y1) = (0.0, 1.0, 0.0, 1.0);
        }
        let pad = |a: f64, b: f64| {
            let d = if b > a { (b - a) * 0.05 } else { a.abs().max(1.0) * 0.05 };
            (a - d, b + d)
        };
        let (x0, x1) = pad(x0, x1);
        let (y0, y1) = pad(y0, y1);
        let mut chart = ChartBuilder::on(area)
            .caption(&panel.title, ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_desc(&panel.x_label)
            .y_desc(&panel.y_label)
            .label_style(("sans-serif", 13))
            .light_line_style(RGBColor(235, 235, 235))
            .draw()
            .map_err(err)?;
        for (i, s) in panel.series.iter().enumerate() {
            let c = colour(s.colour.unwrap_or(i));
            let data: Vec<(f64, f64)> = s
                .points
                .iter()
                .copied()
                .filter(|p| p.0.is_finite() && p.1.is_finite())
                .collect();
            let drawn = match s.mark {
                Mark::Line => chart
                    .draw_series(LineSeries::new(data, c.stroke_width(2)))
                    .map_err(err)?,
                Mark::Dots => chart
                    .draw_series(data.into_iter().map(|p| Circle::new(p, 3, c.filled())))
                    .map_err(err)?,
            };
            drawn
                .label(s.name.clone())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], c.stroke_width(2)));
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK.mix(0.3))
            .label_font(("sans-serif", 12))
            .position(SeriesLabelPosition::UpperLeft)
            .draw()
            .map_err(err)?;
    }
    Ok(())
}

/// PNG bytes of an RGB8 image (the png crate).
fn encode_png(rgb: &[u8], width: u32, height: u32) -> Result<Vec<u8>> {
    let mut out = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut out, width, height);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        let mut w = enc.write_header().map_err(|e| anyhow!("PNG: {e}"))?;
        w.write_image_data(rgb).map_err(|e| anyhow!("PNG: {e}"))?;
    }
    Ok(out)
}
