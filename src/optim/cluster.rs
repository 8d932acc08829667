//! Sorting the end points of a multistart into distinct optima and zones.
//!
//! Two end points are the same optimum when their objectives agree to a relative tolerance
//! and their designs lie within a distance (the largest coordinate difference, in design
//! space scaled to the bounds) of each other or of each other's equivalent (a mirror
//! image, say), as MATLAB's MultiStart merges with its XTolerance and FunctionTolerance.
//! Optima are then grouped into zones of objective value: between given thresholds, or
//! split at the large gaps of the sorted values.

use serde::Serialize;

/// One end point offered for clustering.
#[derive(Debug, Clone)]
pub struct EndPoint {
    /// The design scaled to the bounds (each coordinate in [0, 1]).
    pub x: Vec<f64>,
    /// The objective as the problem states it (larger is better when maximizing).
    pub objective: f64,
}

/// Settings of the clustering.
#[derive(Debug, Clone)]
pub struct ClusterSettings {
    pub x_tolerance: f64,
    /// Relative.
    pub objective_tolerance: f64,
    /// Larger objectives are better.
    pub maximize: bool,
    /// Boundaries between zones, best first; empty: split at gaps.
    pub thresholds: Vec<f64>,
}

/// A distinct optimum and the end points that reached it.
#[derive(Debug, Clone, Serialize)]
pub struct Optimum {
    /// Index of the best end point that reached it (its representative).
    pub representative: usize,
    pub objective: f64,
    /// Every end point (index into the input) that reached it.
    pub members: Vec<usize>,
}

/// A zone: a band of objective values.
#[derive(Debug, Clone, Serialize)]
pub struct Zone {
    /// 1 for the best zone.
    pub rank: usize,
    /// The band `[low, high)` (open-ended at the outer zones), in objective units.
    pub low: Option<f64>,
    pub high: Option<f64>,
    /// Indices into the optima, best first.
    pub optima: Vec<usize>,
    /// Number of end points in the zone.
    pub count: usize,
    pub best: f64,
    pub worst: f64,
}

/// The result of clustering.
#[derive(Debug, Clone, Serialize)]
pub struct Clustering {
    /// Distinct optima, best first.
    pub optima: Vec<Optimum>,
    pub zones: Vec<Zone>,
    /// For each end point, its optimum (index into `optima`).
    pub optimum_of: Vec<usize>,
    /// For each end point, its zone's rank.
    pub zone_of: Vec<usize>,
}

/// Clusters `points`; `equivalent` maps a scaled design to another scaled design of the
/// same geometry (or `None`).
pub fn cluster(
    points: &[EndPoint],
    settings: &ClusterSettings,
    equivalent: &dyn Fn(&[f64]) -> Option<Vec<f64>>,
) -> Clustering {
    let better = |a: f64, b: f64| if settings.maximize { a > b } else { a < b };
    let mut order: Vec<usize> = (0..points.len()).collect();
    order.sort_by(|&a, &b| {
        let (fa, fb) = (points[a].objective, points[b].objective);
        let c = if settings.maximize {
            fb.total_cmp(&fa)
        } else {
            fa.total_cmp(&fb)
        };
        c.then(a.cmp(&b))
    });
    let mut optima: Vec<Optimum> = Vec::new();
    let mut mirrors: Vec<Option<Vec<f64>>> = Vec::new();
    let mut optimum_of = vec![0; points.len()];
    for &i in &order {
        let p = &points[i];
        let found = optima.iter().zip(&mirrors).position(|(o, mirror)| {
            let q = &points[o.representative];
            let close_f = (p.objective - q.objective).abs()
                <= settings.objective_tolerance * q.objective.abs().max(1.0);
            close_f
                && (distance(&p.x, &q.x) <= settings.x_tolerance
                    || mirror
                        .as_ref()
                        .is_some_and(|m| distance(&p.x, m) <= settings.x_tolerance))
        });
        match found {
            Some(k) => {
                optima[k].members.push(i);
                optimum_of[i] = k;
            }
            None => {
                optimum_of[i] = optima.len();
                mirrors.push(equivalent(&p.x));
                optima.push(Optimum {
                    representative: i,
                    objective: p.objective,
                    members: vec![i],
                });
            }
        }
    }
    let bands = if settings.thresholds.is_empty() {
        gap_thresholds(&optima, settings)
    } else {
        let mut t = settings.thresholds.clone();
        t.sort_by(|a, b| {
            if settings.maximize {
                b.total_cmp(a)
            } else {
                a.total_cmp(b)
            }
        });
        t
    };
    // zone rank: 1 + the number of thresholds the optimum does not reach
    let rank_of = |f: f64| 1 + bands.iter().filter(|&&t| better(t, f)).count();
    let mut zones: Vec<Zone> = (0..=bands.len())
        .map(|k| {
            let (hi, lo) = (
                if k == 0 { None } else { Some(bands[k - 1]) },
                bands.get(k).copied(),
            );
            let (low, high) = if settings.maximize {
                (lo, hi)
            } else {
                (hi, lo)
            };
            Zone {
                rank: k + 1,
                low,
                high,
                optima: Vec::new(),
                count: 0,
                best: f64::NAN,
                worst: f64::NAN,
            }
        })
        .collect();
    for (k, o) in optima.iter().enumerate() {
        let z = &mut zones[rank_of(o.objective) - 1];
        if z.optima.is_empty() {
            z.best = o.objective;
        }
        z.optima.push(k);
        z.count += o.members.len();
        z.worst = o.objective;
    }
    let zone_of = optimum_of
        .iter()
        .map(|&k| rank_of(optima[k].objective))
        .collect();
    Clustering {
        optima,
        zones,
        optimum_of,
        zone_of,
    }
}

/// Thresholds at the large gaps of the sorted optimum values: a gap splits two zones when
/// it is wider than a tenth of the whole spread and than 100 objective tolerances.
fn gap_thresholds(optima: &[Optimum], settings: &ClusterSettings) -> Vec<f64> {
    let values: Vec<f64> = optima.iter().map(|o| o.objective).collect();
    let (Some(first), Some(last)) = (values.first(), values.last()) else {
        return Vec::new();
    };
    let spread = (first - last).abs();
    let min_gap = (0.1 * spread).max(100.0 * settings.objective_tolerance * first.abs().max(1.0));
    values
        .windows(2)
        .filter(|w| (w[0] - w[1]).abs() > min_gap)
        .map(|w| 0.5 * (w[0] + w[1]))
        .collect()
}

fn distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .fold(0.0, |m: f64, (x, y)| m.max((x - y).abs()))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(x: &[f64], f: f64) -> EndPoint {
        EndPoint {
            x: x.to_vec(),
            objective: f,
        }
    }

    #[test]
    fn merges_equal_optima_and_mirror_images() {
        let pts = [
            p(&[0.2, 0.5], 10.0),
            p(&[0.2000001, 0.5], 10.0),
            p(&[0.8, 0.5], 10.0),
            p(&[0.5, 0.1], 8.0),
        ];
        let s = ClusterSettings {
            x_tolerance: 1e-3,
            objective_tolerance: 1e-6,
            maximize: true,
            thresholds: vec![],
        };
        let no_mirror = cluster(&pts, &s, &|_| None);
        assert_eq!(no_mirror.optima.len(), 3);
        let mirror = |x: &[f64]| Some(vec![1.0 - x[0], x[1]]);
        let merged = cluster(&pts, &s, &mirror);
        assert_eq!(merged.optima.len(), 2);
        assert_eq!(merged.optima[0].members, vec![0, 1, 2]);
        assert_eq!(merged.optimum_of, vec![0, 0, 0, 1]);
    }

    #[test]
    fn zones_from_thresholds_and_from_gaps() {
        let pts: Vec<EndPoint> = [12.9, 12.8, 12.3, 11.5, 11.4, 9.0]
            .iter()
            .enumerate()
            .map(|(i, &f)| p(&[i as f64 / 10.0], f))
            .collect();
        let mut s = ClusterSettings {
            x_tolerance: 1e-3,
            objective_tolerance: 1e-6,
            maximize: true,
            thresholds: vec![11.0, 12.7, 12.0],
        };
        let c = cluster(&pts, &s, &|_| None);
        assert_eq!(
            c.zones.iter().map(|z| z.count).collect::<Vec<_>>(),
            vec![2, 1, 2, 1]
        );
        assert_eq!(c.zone_of, vec![1, 1, 2, 3, 3, 4]);
        assert_eq!((c.zones[0].best, c.zones[0].worst), (12.9, 12.8));
        s.thresholds.clear();
        let g = cluster(&pts, &s, &|_| None);
        // gaps 0.1, 0.5, 0.8, 0.1, 2.4 against a tenth of the spread, 0.39: three split
        assert_eq!(g.zones.len(), 4);
        assert_eq!(g.zone_of, vec![1, 1, 2, 3, 3, 4]);
    }

    #[test]
    fn minimization_puts_low_values_first() {
        let pts = [p(&[0.1], 3.0), p(&[0.9], 1.0)];
        let s = ClusterSettings {
            x_tolerance: 1e-3,
            objective_tolerance: 1e-6,
            maximize: false,
            thresholds: vec![2.0],
        };
        let c = cluster(&pts, &s, &|_| None);
        assert_eq!(c.optima[0].objective, 1.0);
        assert_eq!(c.zone_of, vec![2, 1]);
    }
}
