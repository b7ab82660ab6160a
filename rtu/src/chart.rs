//! SVG line charts (plotters) for the reports: one series per line, points marked.

use plotters::prelude::*;
use std::path::Path;

/// A named series of `(x, y)` points, drawn in order.
pub type Series = (String, Vec<(f64, f64)>);

/// Axis ranges covering every point, padded by 5% (and never empty).
fn range(v: impl Iterator<Item = f64> + Clone) -> std::ops::Range<f64> {
    let lo = v.clone().fold(f64::INFINITY, f64::min);
    let hi = v.fold(f64::NEG_INFINITY, f64::max);
    if !lo.is_finite() || !hi.is_finite() {
        return 0.0..1.0;
    }
    let pad = ((hi - lo) * 0.05).max(1e-9);
    (lo - pad)..(hi + pad)
}

/// Writes a line chart of `series` to `path` (SVG). `y_from_zero` starts the y axis at 0.
pub fn line_chart(
    path: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
    y_from_zero: bool,
) -> Result<(), String> {
    let err = |e: &dyn std::fmt::Display| format!("chart {}: {e}", path.display());
    let root = SVGBackend::new(path, (900, 560)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| err(&e))?;
    let xs = range(series.iter().flat_map(|s| s.1.iter().map(|p| p.0)));
    let mut ys = range(series.iter().flat_map(|s| s.1.iter().map(|p| p.1)));
    if y_from_zero {
        ys.start = 0.0;
    }
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 20))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(60)
        .build_cartesian_2d(xs, ys)
        .map_err(|e| err(&e))?;
    chart
        .configure_mesh()
        .x_desc(x_label)
        .y_desc(y_label)
        .draw()
        .map_err(|e| err(&e))?;
    for (i, (name, pts)) in series.iter().enumerate() {
        let color = Palette99::pick(i).to_rgba();
        chart
            .draw_series(LineSeries::new(pts.iter().copied(), color.stroke_width(2)))
            .map_err(|e| err(&e))?
            .label(name.as_str())
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 18, y)], color.stroke_width(2))
            });
        chart
            .draw_series(pts.iter().map(|&p| Circle::new(p, 3, color.filled())))
            .map_err(|e| err(&e))?;
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .position(SeriesLabelPosition::LowerRight)
        .draw()
        .map_err(|e| err(&e))?;
    root.present().map_err(|e| err(&e))?;
    Ok(())
}

/// A point of a scatter chart: its group (one colour and legend entry per group), a label drawn next to
/// it when it is on the front, and whether it is on the Pareto front.
#[derive(Clone, Debug)]
pub struct Point {
    pub x: f64,
    pub y: f64,
    pub label: String,
    pub group: String,
    pub front: bool,
}

/// Writes a scatter chart of `pts` to `path` (SVG) with a logarithmic x axis (cost), one colour per group,
/// and the front points joined in x order by a black line and labelled.
pub fn scatter_chart(
    path: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    pts: &[Point],
) -> Result<(), String> {
    let err = |e: &dyn std::fmt::Display| format!("chart {}: {e}", path.display());
    if pts
        .iter()
        .any(|p| p.x.is_nan() || p.x <= 0.0 || !p.y.is_finite())
    {
        return Err(format!(
            "chart {}: every point needs a positive cost and a finite value",
            path.display()
        ));
    }
    let root = SVGBackend::new(path, (1000, 640)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| err(&e))?;
    let xs = range(pts.iter().map(|p| p.x.ln()));
    let ys = range(pts.iter().map(|p| p.y));
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 20))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(60)
        .build_cartesian_2d((xs.start.exp()..xs.end.exp()).log_scale(), ys)
        .map_err(|e| err(&e))?;
    chart
        .configure_mesh()
        .x_desc(x_label)
        .y_desc(y_label)
        .x_labels(8)
        .x_label_formatter(&|v| {
            if *v >= 1000.0 {
                format!("{:.0}k", v / 1000.0)
            } else {
                format!("{v:.0}")
            }
        })
        .max_light_lines(1)
        .draw()
        .map_err(|e| err(&e))?;
    let mut groups: Vec<&str> = pts.iter().map(|p| p.group.as_str()).collect();
    groups.sort_unstable();
    groups.dedup();
    for (i, g) in groups.iter().enumerate() {
        let color = Palette99::pick(i).to_rgba();
        chart
            .draw_series(
                pts.iter()
                    .filter(|p| p.group == *g)
                    .map(|p| Circle::new((p.x, p.y), 4, color.filled())),
            )
            .map_err(|e| err(&e))?
            .label(*g)
            .legend(move |(x, y)| Circle::new((x + 9, y), 4, color.filled()));
    }
    let mut front: Vec<&Point> = pts.iter().filter(|p| p.front).collect();
    front.sort_by(|a, b| a.x.total_cmp(&b.x));
    chart
        .draw_series(LineSeries::new(
            front.iter().map(|p| (p.x, p.y)),
            BLACK.stroke_width(1),
        ))
        .map_err(|e| err(&e))?
        .label("Pareto front")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], BLACK.stroke_width(1)));
    chart
        .draw_series(front.iter().map(|p| {
            Text::new(
                p.label.clone(),
                (p.x, p.y),
                ("sans-serif", 12).into_font().color(&BLACK),
            )
        }))
        .map_err(|e| err(&e))?;
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .position(SeriesLabelPosition::UpperRight)
        .draw()
        .map_err(|e| err(&e))?;
    root.present().map_err(|e| err(&e))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn writes_an_svg_with_every_series_named() {
        let dir = std::env::temp_dir().join(format!("rtu-chart-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let p = dir.join("c.svg");
        let s = vec![
            ("alpha".to_string(), vec![(1.0, 2.0), (2.0, 3.5)]),
            ("beta".to_string(), vec![(1.0, 1.0), (4.0, 0.5)]),
        ];
        line_chart(&p, "t", "x", "y", &s, true).unwrap();
        let text = std::fs::read_to_string(&p).unwrap();
        assert!(text.starts_with("<svg") && text.contains("alpha") && text.contains("beta"));
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn scatter_labels_the_front_and_rejects_a_zero_cost() {
        let dir = std::env::temp_dir().join(format!("rtu-scatter-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let p = dir.join("s.svg");
        let pt = |x: f64, y: f64, label: &str, front: bool| Point {
            x,
            y,
            label: label.into(),
            group: "g".into(),
            front,
        };
        let pts = vec![
            pt(100.0, 2.0, "cheap", true),
            pt(5000.0, 3.0, "hidden", false),
        ];
        scatter_chart(&p, "t", "x", "y", &pts).unwrap();
        let text = std::fs::read_to_string(&p).unwrap();
        assert!(text.contains("cheap") && !text.contains("hidden"));
        let bad = vec![pt(0.0, 1.0, "zero", true)];
        assert!(scatter_chart(&p, "t", "x", "y", &bad).is_err());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
