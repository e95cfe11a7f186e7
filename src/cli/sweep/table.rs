//! The sweep's table: one CSV row per run (its columns are listed in `sweep --help`), and
//! the plot of the observed frequencies.

use super::super::error::{CliError, CliResult};
use super::super::output::number;
use rotorflow::algebra::plane_name;
use rotorflow::dynamics::trajectory::{ProjectedObservables, projection_planes};
use rotorflow::viz::plot::{PlotSpec, Series, line_plot, subscript};

/// One row of the sweep table.
pub(super) struct Row {
    /// The run's index in the grid.
    pub run: usize,
    /// The parameter values.
    pub values: Vec<f64>,
    /// The observables of the 3D projection.
    pub observables: ProjectedObservables,
    /// The largest relative drift of the Manakov integrals (0 where there are none).
    pub manakov_drift: f64,
    /// The largest relative drift of the energy.
    pub energy_drift: f64,
    /// The largest relative drift of the Casimirs.
    pub casimir_drift: f64,
}

pub(super) fn table_csv(
    names: &[String],
    dim: usize,
    axes: [usize; 3],
    rows: &[Row],
    header: bool,
) -> String {
    let mut out = String::new();
    if header {
        let mut h = vec!["run".to_string()];
        h.extend(names.iter().cloned());
        for (a, b) in projection_planes(axes) {
            let p = plane_name(dim, a, b);
            h.push(format!("freq_{p}"));
            h.push(format!("amp_{p}"));
            h.push(format!("mean_{p}"));
        }
        // The drifts that end the table keep their places; the Manakov integrals' comes
        // before the flips.
        h.extend(
            [
                "manakov_drift",
                "flips",
                "first_flip",
                "energy_drift",
                "casimir_drift",
            ]
            .iter()
            .map(|s| s.to_string()),
        );
        out.push_str(&h.join(","));
        out.push('\n');
    }
    for r in rows {
        out.push_str(&row_line(r));
        out.push('\n');
    }
    out
}

/// One row of the table, without the newline.
pub(super) fn row_line(r: &Row) -> String {
    let mut row = vec![r.run.to_string()];
    row.extend(r.values.iter().map(|v| number(*v)));
    let o = &r.observables;
    for k in 0..3 {
        row.push(number(o.frequency[k]));
        row.push(number(o.amplitude[k]));
        row.push(number(o.mean[k]));
    }
    row.push(number(r.manakov_drift));
    row.push(o.flips.to_string());
    row.push(o.first_flip.map(number).unwrap_or_default());
    row.push(number(r.energy_drift));
    row.push(number(r.casimir_drift));
    row.join(",")
}

pub(super) fn sweep_plot(names: &[String], dim: usize, rows: &[Row]) -> CliResult<String> {
    let Some(first) = rows.first() else {
        return Err(CliError::input("--plot: this shard has no runs to plot"));
    };
    let mut series: Vec<Series> = first
        .observables
        .planes
        .iter()
        .enumerate()
        .map(|(k, &(a, b))| Series {
            name: format!(
                "observed frequency of ω{}",
                subscript(&plane_name(dim, a, b))
            ),
            points: rows
                .iter()
                .map(|r| (r.values[0], r.observables.frequency[k]))
                .collect(),
        })
        .collect();
    for s in &mut series {
        s.points.sort_by(|p, q| p.0.total_cmp(&q.0));
    }
    line_plot(
        &PlotSpec {
            title: &format!("3D observables against the parameter {}", names[0]),
            x_label: &names[0],
            y_label: "angular frequency (rad per unit time)",
            log_y: false,
            markers: true,
        },
        &series,
    )
    .map_err(|e| CliError::runtime(format!("cannot draw the plot: {e}")))
}
