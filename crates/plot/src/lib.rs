//! Figures: panels of x-y series drawn with plotters, as SVG text or PNG bytes, with the
//! DejaVu Sans font compiled in (`assets/fonts`) so that text renders the same on every
//! machine: PNG text is rasterised from it; SVG text names it and a standalone SVG (or an
//! HTML page, [`font_face_css`]) carries it as an `@font-face`.
//!
//! Writing files is the caller's business (the CLI writes atomically).
#![deny(missing_docs)]

use std::sync::Once;

use base64::Engine;
use plotters::chart::ChartContext;
use plotters::coord::cartesian::Cartesian2d;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use plotters::style::{register_font, FontStyle};
use thiserror::Error;

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mark {
    /// Connected line.
    Line,
    /// Connected dashed line.
    Dashed,
    /// Separate dots (with vertical error bars when the series has them).
    Dots,
    /// A shaded area: the points are its outline, in order (a band's lower edge left to right,
    /// then its upper edge right to left), drawn faint under the other series.
    Area,
}

/// One named series.
#[derive(Debug, Clone)]
pub struct Series {
    /// Legend text (empty: not in the legend).
    pub name: String,
    /// Points (x, y); non-finite ones are skipped.
    pub points: Vec<(f64, f64)>,
    /// Half-heights of vertical error bars, one per point (empty: none).
    pub y_err: Vec<f64>,
    /// Line or dots.
    pub mark: Mark,
    /// Palette index (default: the series' position), so that related series share a colour.
    pub colour: Option<usize>,
}

impl Series {
    /// A series without error bars.
    pub fn new(name: impl Into<String>, points: Vec<(f64, f64)>, mark: Mark, colour: Option<usize>) -> Self {
        Self {
            name: name.into(),
            points,
            y_err: Vec::new(),
            mark,
            colour,
        }
    }
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
    /// Draw the line y = 0.
    pub zero_line: bool,
    /// Limits of the y axis, when the data may run far beyond the useful band (relative
    /// errors near zero thrust): points outside are drawn on the edge as triangles.
    pub y_clip: Option<(f64, f64)>,
    /// One unit is as long on both axes (airfoil sections: no stretched outlines).
    pub equal_aspect: bool,
}

impl Panel {
    /// A chart of `series`: no zero line, the y axis fitted to the data, free aspect.
    pub fn new(
        title: impl Into<String>,
        x_label: impl Into<String>,
        y_label: impl Into<String>,
        series: Vec<Series>,
    ) -> Self {
        Self {
            title: title.into(),
            x_label: x_label.into(),
            y_label: y_label.into(),
            series,
            zero_line: false,
            y_clip: None,
            equal_aspect: false,
        }
    }
}

/// The useful band of a relative-error axis [%]: beyond it a point says only "far off", and
/// a ±600 % axis would hide the band where the model is judged.
pub const ERROR_AXIS: (f64, f64) = (-100.0, 100.0);

/// Panels on a grid.
#[derive(Debug, Clone)]
pub struct Figure {
    /// Panels, row by row.
    pub panels: Vec<Panel>,
    /// Panels per row.
    pub columns: usize,
    /// Width [px].
    pub width: u32,
    /// Height [px].
    pub height: u32,
}

/// Drawing failed.
#[derive(Debug, Error)]
#[error("plot: {0}")]
pub struct PlotError(String);

impl PlotError {
    /// An error with this message.
    pub fn from_message(m: String) -> Self {
        Self(m)
    }
}

/// Family name under which the bundled font is registered and embedded.
pub const FONT_FAMILY: &str = "PropbetSans";
static FONT: Once = Once::new();
const FONT_BYTES: &[u8] = include_bytes!("../../../assets/fonts/DejaVuSans.ttf");

fn register() {
    FONT.call_once(|| {
        // The font is compiled in; registering it cannot meet a missing file.
        let _ = register_font(FONT_FAMILY, FontStyle::Normal, FONT_BYTES);
    });
}

/// CSS `@font-face` carrying the bundled font (base64), for pages that inline the SVGs.
pub fn font_face_css() -> String {
    format!(
        "@font-face{{font-family:{FONT_FAMILY};src:url(data:font/ttf;base64,{}) format('truetype');}}",
        base64::engine::general_purpose::STANDARD.encode(FONT_BYTES)
    )
}

/// Colour of the i-th series (a colour-blind-safe palette, Okabe-Ito).
pub fn colour(i: usize) -> RGBColor {
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

/// The figure as an SVG element (no XML declaration, no embedded font: for inlining in a page
/// that carries [`font_face_css`]).
pub fn svg_inline(fig: &Figure) -> Result<String, PlotError> {
    register();
    let mut text = String::new();
    {
        let root = SVGBackend::with_string(&mut text, (fig.width, fig.height)).into_drawing_area();
        render(&root, fig)?;
        root.present().map_err(|e| PlotError(e.to_string()))?;
    }
    if let Some(i) = text.find("<svg") {
        text.drain(..i);
    }
    Ok(text)
}

/// The figure as a standalone SVG file carrying its font.
pub fn svg(fig: &Figure) -> Result<String, PlotError> {
    let mut text = svg_inline(fig)?;
    let close = text
        .find('>')
        .ok_or_else(|| PlotError("SVG without a root element".into()))?;
    text.insert_str(close + 1, &format!("<style>{}</style>", font_face_css()));
    Ok(text)
}

/// The figure as PNG bytes.
pub fn png(fig: &Figure) -> Result<Vec<u8>, PlotError> {
    register();
    let mut rgb = vec![255u8; (fig.width * fig.height * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut rgb, (fig.width, fig.height)).into_drawing_area();
        render(&root, fig)?;
        root.present().map_err(|e| PlotError(e.to_string()))?;
    }
    encode_png(&rgb, fig.width, fig.height)
}

fn range(panel: &Panel) -> (f64, f64, f64, f64) {
    let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY);
    for s in &panel.series {
        for (i, p) in s.points.iter().enumerate() {
            if !(p.0.is_finite() && p.1.is_finite()) {
                continue;
            }
            let e = s.y_err.get(i).copied().filter(|e| e.is_finite()).unwrap_or(0.0);
            x0 = x0.min(p.0);
            x1 = x1.max(p.0);
            y0 = y0.min(p.1 - e);
            y1 = y1.max(p.1 + e);
        }
    }
    if panel.zero_line && y0.is_finite() {
        y0 = y0.min(0.0);
        y1 = y1.max(0.0);
    }
    if !x0.is_finite() {
        return (0.0, 1.0, 0.0, 1.0);
    }
    let pad = |a: f64, b: f64| {
        let d = if b > a { (b - a) * 0.05 } else { a.abs().max(1.0) * 0.05 };
        (a - d, b + d)
    };
    let (x0, x1) = pad(x0, x1);
    let (y0, y1) = match panel.y_clip {
        Some((lo, hi)) => {
            let (a, b) = pad(y0.max(lo), y1.min(hi));
            (a.max(lo), b.min(hi))
        }
        None => pad(y0, y1),
    };
    (x0, x1, y0, y1)
}

/// `ranges` widened on one axis so that a unit is as long on both over a plot area of `(pw, ph)`
/// pixels, each axis centred where it was.
fn equal_aspect((x0, x1, y0, y1): (f64, f64, f64, f64), (pw, ph): (f64, f64)) -> (f64, f64, f64, f64) {
    let (sx, sy) = ((x1 - x0) / pw, (y1 - y0) / ph);
    if sx > sy {
        let c = 0.5 * (y0 + y1);
        (x0, x1, c - 0.5 * sx * ph, c + 0.5 * sx * ph)
    } else {
        let c = 0.5 * (x0 + x1);
        (c - 0.5 * sy * pw, c + 0.5 * sy * pw, y0, y1)
    }
}

/// A tick label with no more digits than it needs: "2000", not "2000.0"; "0", not "-0.0";
/// "0.05"; "1.2e-5" for small values.
fn tick(v: &f64) -> String {
    let v = *v;
    if v.abs() < 1e-12 {
        return "0".into();
    }
    if v.abs() < 1e-3 || v.abs() >= 1e7 {
        return format!("{v:.1e}");
    }
    let s = format!("{v:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".into()
    } else {
        s.to_string()
    }
}

/// The corner of the plot area with the fewest points (in a box of a third of each axis),
/// where the legend hides the least.
fn legend_corner(panel: &Panel, (x0, x1, y0, y1): (f64, f64, f64, f64)) -> SeriesLabelPosition {
    let fx = |x: f64| (x - x0) / (x1 - x0);
    let fy = |y: f64| (y - y0) / (y1 - y0);
    let corners = [
        (SeriesLabelPosition::UpperRight, true, true),
        (SeriesLabelPosition::UpperLeft, false, true),
        (SeriesLabelPosition::LowerRight, true, false),
        (SeriesLabelPosition::LowerLeft, false, false),
    ];
    let count = |right: bool, upper: bool| {
        panel
            .series
            .iter()
            .flat_map(|s| s.points.iter())
            .filter(|p| {
                let (x, y) = (fx(p.0), fy(p.1.clamp(y0, y1)));
                (if right { x > 0.6 } else { x < 0.4 }) && (if upper { y > 0.6 } else { y < 0.4 })
            })
            .count()
    };
    corners
        .into_iter()
        .min_by_key(|&(_, r, u)| count(r, u))
        .map_or(SeriesLabelPosition::UpperRight, |c| c.0)
}

/// One series of a panel: its line, dashes or dots with error bars, its legend entry, and its
/// points beyond the clipped y axis `(y0, y1)` as triangles on the edge. Whether it has a
/// legend entry.
fn draw_series<'a, DB: DrawingBackend + 'a>(
    chart: &mut ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    s: &Series,
    i: usize,
    (y0, y1): (f64, f64),
) -> Result<bool, PlotError> {
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| PlotError(format!("{e:?}"));
    let c = colour(s.colour.unwrap_or(i));
    let data: Vec<(usize, (f64, f64))> = s
        .points
        .iter()
        .copied()
        .enumerate()
        .filter(|(_, p)| p.0.is_finite() && p.1.is_finite())
        .collect();
    // Points beyond a clipped axis go on its edge (marked below).
    let clip = |p: (f64, f64)| (p.0, p.1.clamp(y0, y1));
    let outside: Vec<(f64, f64)> = if s.mark == Mark::Area {
        Vec::new()
    } else {
        data.iter().map(|d| d.1).filter(|p| p.1 < y0 || p.1 > y1).collect()
    };
    let xy = data.iter().map(|d| clip(d.1));
    let drawn = match s.mark {
        Mark::Area => chart
            .draw_series(std::iter::once(Polygon::new(
                xy.collect::<Vec<_>>(),
                c.mix(0.15).filled(),
            )))
            .map_err(err)?,
        Mark::Line => chart.draw_series(LineSeries::new(xy, c.stroke_width(2))).map_err(err)?,
        Mark::Dashed => chart
            .draw_series(DashedLineSeries::new(xy, 6, 4, c.stroke_width(2)))
            .map_err(err)?,
        Mark::Dots => {
            let bars: Vec<(f64, f64, f64)> = data
                .iter()
                .filter_map(|(k, p)| {
                    s.y_err
                        .get(*k)
                        .filter(|e| e.is_finite() && **e > 0.0)
                        .map(|e| (p.0, p.1, *e))
                })
                .collect();
            chart
                .draw_series(
                    bars.into_iter()
                        .map(|(x, y, e)| ErrorBar::new_vertical(x, y - e, y, y + e, c.stroke_width(1), 6)),
                )
                .map_err(err)?;
            let inside: Vec<(f64, f64)> = xy.filter(|p| p.1 > y0 && p.1 < y1).collect();
            chart
                .draw_series(inside.into_iter().map(|p| Circle::new(p, 3, c.filled())))
                .map_err(err)?
        }
    };
    let named = !s.name.is_empty();
    if named {
        let dots = s.mark == Mark::Dots;
        drawn
            .label(s.name.clone())
            .legend(move |(x, y)| -> DynElement<'static, DB, (i32, i32)> {
                if dots {
                    Circle::new((x + 8, y), 3, c.filled()).into_dyn()
                } else {
                    PathElement::new(vec![(x, y), (x + 16, y)], c.stroke_width(2)).into_dyn()
                }
            });
    }
    // Off-scale points: a triangle on the edge, pointing the way they went.
    chart
        .draw_series(outside.iter().map(|&(x, y)| {
            let (edge, dy) = if y > y1 { (y1, -1) } else { (y0, 1) };
            let tip = (0, 0);
            let base = (-5, 8 * dy);
            let base2 = (5, 8 * dy);
            EmptyElement::at((x, edge)) + Polygon::new(vec![tip, base, base2], c.stroke_width(1))
        }))
        .map_err(err)?;
    Ok(named)
}

fn render<DB: DrawingBackend>(root: &DrawingArea<DB, plotters::coord::Shift>, fig: &Figure) -> Result<(), PlotError> {
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| PlotError(format!("{e:?}"));
    root.fill(&WHITE).map_err(err)?;
    let cols = fig.columns.max(1);
    let rows = fig.panels.len().div_ceil(cols).max(1);
    let areas = root.split_evenly((rows, cols));
    for (panel, area) in fig.panels.iter().zip(areas.iter()) {
        let (mut x0, mut x1, mut y0, mut y1) = range(panel);
        if panel.equal_aspect {
            // The plot area without the caption, margins and label areas (as built below).
            let (w, h) = area.dim_in_pixel();
            let plot = (
                f64::from(w.saturating_sub(64 + 24)).max(1.0),
                f64::from(h.saturating_sub(40 + 24 + 30)).max(1.0),
            );
            (x0, x1, y0, y1) = equal_aspect((x0, x1, y0, y1), plot);
        }
        let mut chart = ChartBuilder::on(area)
            .caption(&panel.title, (FONT_FAMILY, 17))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(64)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(err)?;
        // A count on the x axis (ladder steps): integer ticks only.
        let xs = || panel.series.iter().flat_map(|s| s.points.iter().map(|p| p.0));
        let counts = xs().count() > 0 && xs().all(|x| x.fract() == 0.0 && (0.0..=50.0).contains(&x));
        let x_labels = if counts {
            (x1 - x0).round().max(1.0) as usize + 1
        } else {
            10
        };
        let x_tick = |v: &f64| {
            if counts && (v.fract().abs() > 1e-9) {
                String::new()
            } else {
                tick(v)
            }
        };
        chart
            .configure_mesh()
            .x_labels(x_labels)
            .x_desc(&panel.x_label)
            .y_desc(&panel.y_label)
            .label_style((FONT_FAMILY, 12))
            .x_label_formatter(&x_tick)
            .y_label_formatter(&tick)
            .axis_desc_style((FONT_FAMILY, 13))
            .light_line_style(RGBColor(235, 235, 235))
            .draw()
            .map_err(err)?;
        if panel.zero_line {
            chart
                .draw_series(LineSeries::new(
                    vec![(x0, 0.0), (x1, 0.0)],
                    BLACK.mix(0.5).stroke_width(1),
                ))
                .map_err(err)?;
        }
        let mut legend = false;
        for (i, s) in panel.series.iter().enumerate() {
            legend |= draw_series(&mut chart, s, i, (y0, y1))?;
        }
        if legend {
            chart
                .configure_series_labels()
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK.mix(0.3))
                .label_font((FONT_FAMILY, 11))
                .position(legend_corner(panel, (x0, x1, y0, y1)))
                .draw()
                .map_err(err)?;
        }
    }
    Ok(())
}

/// PNG bytes of an RGB8 image (the png crate).
fn encode_png(rgb: &[u8], width: u32, height: u32) -> Result<Vec<u8>, PlotError> {
    let mut out = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut out, width, height);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        let mut w = enc.write_header().map_err(|e| PlotError(format!("PNG: {e}")))?;
        w.write_image_data(rgb).map_err(|e| PlotError(format!("PNG: {e}")))?;
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fig() -> Figure {
        let mut s = Series::new(
            "measured",
            vec![(0.0, 1.0), (1.0, 2.0), (2.0, f64::NAN)],
            Mark::Dots,
            None,
        );
        s.y_err = vec![0.1, 0.2, 0.3];
        Figure {
            panels: vec![
                Panel {
                    title: "CT".into(),
                    x_label: "J".into(),
                    y_label: "CT".into(),
                    series: vec![
                        s,
                        Series::new("predicted", vec![(0.0, 1.1), (1.0, 2.1)], Mark::Line, Some(0)),
                    ],
                    zero_line: true,
                    y_clip: None,
                    equal_aspect: false,
                },
                Panel {
                    title: "empty".into(),
                    x_label: "x".into(),
                    y_label: "y".into(),
                    series: vec![],
                    zero_line: false,
                    y_clip: None,
                    equal_aspect: false,
                },
            ],
            columns: 2,
            width: 640,
            height: 320,
        }
    }

    #[test]
    fn svg_names_the_bundled_font_and_carries_it() {
        let inline = svg_inline(&fig()).unwrap();
        assert!(inline.starts_with("<svg"));
        assert!(inline.contains(FONT_FAMILY));
        assert!(inline.contains("measured") && inline.contains("predicted"));
        let full = svg(&fig()).unwrap();
        assert!(full.contains("@font-face"));
        assert!(full.len() > inline.len() + 500_000, "font embedded");
    }

    #[test]
    fn a_clipped_axis_keeps_the_band_and_marks_what_is_beyond() {
        let mut p = fig().panels.remove(0);
        p.series = vec![Series::new(
            "err",
            vec![(0.0, 10.0), (1.0, -20.0), (2.0, 650.0)],
            Mark::Dots,
            None,
        )];
        let free = range(&p);
        assert!(free.3 > 650.0);
        p.y_clip = Some(ERROR_AXIS);
        let (_, _, y0, y1) = range(&p);
        assert!(y0 >= -100.0 && y1 == 100.0, "{y0} {y1}");
        let f = Figure {
            panels: vec![p],
            columns: 1,
            width: 400,
            height: 300,
        };
        // Two dots inside, one triangle on the upper edge.
        let svg = svg_inline(&f).unwrap();
        assert_eq!(svg.matches("<circle").count(), 2 + 1, "two dots and the legend's");
        assert!(svg.contains("<polygon"), "the off-scale point is marked");
    }

    #[test]
    fn the_legend_goes_where_the_data_are_not() {
        let mut p = fig().panels.remove(0);
        p.series = vec![Series::new(
            "a",
            (0..20).map(|k| (f64::from(k), f64::from(k))).collect(),
            Mark::Dots,
            None,
        )];
        // Data on the diagonal from lower left to upper right: an empty corner is upper left
        // or lower right.
        let c = legend_corner(&p, range(&p));
        assert!(matches!(
            c,
            SeriesLabelPosition::UpperLeft | SeriesLabelPosition::LowerRight
        ));
    }

    #[test]
    fn equal_aspect_widens_the_short_axis() {
        // A section (x 0..1, y -0.1..0.15) on 300 x 200 px: y widens to 2/3 of a unit.
        let (x0, x1, y0, y1) = equal_aspect((0.0, 1.0, -0.1, 0.15), (300.0, 200.0));
        assert_eq!((x0, x1), (0.0, 1.0));
        assert!(((y1 - y0) - 2.0 / 3.0).abs() < 1e-12 && ((y0 + y1) / 2.0 - 0.025).abs() < 1e-12);
        // A tall range on a wide area: x widens instead.
        let (x0, x1, ..) = equal_aspect((0.0, 1.0, 0.0, 4.0), (300.0, 200.0));
        assert!(((x1 - x0) - 6.0).abs() < 1e-12);
    }

    #[test]
    fn tick_labels_have_the_digits_they_need() {
        assert_eq!(tick(&2000.0), "2000");
        assert_eq!(tick(&-0.0), "0");
        assert_eq!(tick(&-1e-15), "0");
        assert_eq!(tick(&0.05), "0.05");
        assert_eq!(tick(&(0.1 + 0.2)), "0.3");
        assert_eq!(tick(&-2.5), "-2.5");
        assert_eq!(tick(&1.2e-5), "1.2e-5");
    }

    #[test]
    fn png_is_a_png_with_ink() {
        let bytes = png(&fig()).unwrap();
        assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
        let dec = png::Decoder::new(std::io::Cursor::new(bytes));
        let mut r = dec.read_info().unwrap();
        let mut buf = vec![0; r.output_buffer_size().unwrap()];
        r.next_frame(&mut buf).unwrap();
        assert!(buf.iter().filter(|&&b| b < 128).count() > 1000, "text and lines drawn");
    }
}
