use super::*;

#[test]
fn mirror_images_of_every_pair_are_looked_at_once() {
    // 16 solids, 120 pairs: every pair is a mirror image of exactly one pair looked at
    let pairs = pair_orbits();
    let mut covered = std::collections::BTreeSet::new();
    for &(i, j) in pairs {
        for (a, b) in [
            (i, j),
            (mirrored(i, true), mirrored(j, true)),
            (mirrored(i, false), mirrored(j, false)),
            (
                mirrored(mirrored(i, true), false),
                mirrored(mirrored(j, true), false),
            ),
        ] {
            covered.insert((a.min(b), a.max(b)));
        }
    }
    assert_eq!(covered.len(), 120);
    let joined_pairs = (0..SOLIDS)
        .flat_map(|i| (i + 1..SOLIDS).map(move |j| (i, j)))
        .filter(|&(i, j)| joined(i, j))
        .count();
    assert_eq!(joined_pairs, 16);
    assert!(rows(true).len() < MAX_RULES, "{}", rows(true).len());
    // every hinge's band is looked at against every other solid, once
    let bands = rows(true)
        .iter()
        .flat_map(|r| &r.terms)
        .filter(|t| (BAND_B..=BAND_D_START).contains(&t.a) || t.a >= BAND_B_END)
        .count();
    assert!(bands >= 15, "{bands}");
}

#[test]
fn a_search_answered_by_the_last_one_is_the_search_itself() {
    use rand::{Rng, SeedableRng};
    let mm = 1e-3;
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(43);
    let with_actuator = PartSettings {
        actuator_length: Some(20.0 * mm),
        actuator_height: Some(4.0 * mm),
        ..PartSettings::default()
    };
    let narrow = PartSettings {
        min_slot: 0.3 * mm,
        ..with_actuator.clone()
    };
    let settings = [PartSettings::default(), with_actuator, narrow];
    let mut answered = 0;
    for &kind in HingeKind::ALL {
        let layout = Layout::new(kind, kind);
        for _ in 0..20 {
            let x: Vec<f64> = layout
                .parameters()
                .iter()
                .map(|p| match p.dimension {
                    crate::model::Dimension::Angle => rng.random_range(-0.6..0.6),
                    _ => rng.random_range(0.1..12.0) * mm,
                })
                .collect();
            let g = layout.geometry(&x);
            // each design searched twice in a row under each setting, then under the
            // first again: the second of each pair is the last search's, the others not
            for s in settings.iter().flat_map(|s| [s, s]).chain([&settings[0]]) {
                let n = count(s);
                let (mut kept, mut fresh) = (vec![f64::NAN; n], vec![f64::NAN; n]);
                let last = LAST_SEARCH.with_borrow(|l| l.map(|(k, ..)| k));
                answered += usize::from(last == Some(SearchKey::new(s, &layout, &g)));
                let a = Selection::find(s, &layout, &g, &mut kept);
                let b = Selection::search(s, &layout, &g, &mut fresh);
                let bits = |v: &[f64]| v.iter().map(|m| m.to_bits()).collect::<Vec<_>>();
                assert_eq!(bits(&kept), bits(&fresh), "{kind:?} {x:?} {s:?}");
                assert_eq!((a.nearest, a.link), (b.nearest, b.link));
            }
        }
    }
    assert_eq!(answered, HingeKind::ALL.len() * 20 * settings.len());
}

#[test]
fn a_pair_the_boxes_leave_out_is_no_nearer_than_the_bound() {
    use crate::model::clearance::clearance;
    use rand::{Rng, SeedableRng};
    // convex quadrilaterals of millimetres, from far apart to overlapping, some along
    // the axes as the blocks are: where the boxes say a pair is not below a bound, its
    // clearance is not
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(23);
    let mut left_out = 0;
    for k in 0..20_000 {
        let mut quad = || -> Piece<f64> {
            let (cx, cy) = (rng.random_range(-4e-3..4e-3), rng.random_range(-4e-3..4e-3));
            let (w, h) = (rng.random_range(1e-4..3e-3), rng.random_range(1e-4..3e-3));
            let turn = if k % 3 == 0 {
                0.0
            } else {
                rng.random_range(0.0..6.3)
            };
            let (s, c) = f64::sin_cos(turn);
            [[-w, -h], [w, -h], [w, h], [-w, h]]
                .map(|[x, y]| [cx + c * x - s * y, cy + s * x + c * y])
        };
        let (a, b) = (quad(), quad());
        let bound = rng.random_range(-2e-3..CAP);
        if boxes_apart(&bounds(&a), &bounds(&b), bound) {
            left_out += 1;
            let solid = |p| Solid {
                corners: p,
                sides: &IN_ORDER,
            };
            let (c, _) = clearance(solid(&a), solid(&b));
            assert!(c >= bound, "pair {k}: clearance {c} below {bound}");
        }
    }
    assert!(left_out > 2_000, "{left_out}");
}
