//! The solve of a network on its free degrees of freedom ([`Network::solve_cases_in`]): their
//! numbering, each flexure's terms of the stiffness among them, formed once for a structure
//! ([`Plan`]), the assembly, the `L D L^T` factor and each load case's substitutions. A room
//! of its own because it is what a design's evaluation runs, written for its instruction
//! count over `Jet<8>`, while `structure.rs` says what a network is and reads its
//! displacements; a child of `structure`, so that the buffers' types stay private to it.

use super::super::supports::Constraints;
use super::{Body, Case, Dof, Flexure, Network, NetworkError, SolveBuffers, Solved, Stiffness};
use crate::model::scalar::Scalar;

impl<D: Scalar> Network<D> {
    /// [`Network::solve_cases`] in `buffers`, which a caller keeps from one design to the
    /// next: the evaluation of a small network is otherwise mostly its allocations. A
    /// case's bodies not read are left NaN: the substitutions stop short of them.
    pub fn solve_cases_in<'a>(
        &'a self,
        cases: &[Case<D>],
        buffers: &'a mut SolveBuffers<D>,
    ) -> Result<Solved<'a, D>, NetworkError> {
        let bodies = self.references.len();
        let SolveBuffers {
            index,
            k,
            f,
            moved,
            ends,
            stiffness,
            scaled,
            plan,
        } = buffers;
        // the free numbering is the plan's while the structure is the one it was formed for
        if !plan.fits(bodies, &self.held, &self.flexures) {
            let m = self.free_numbering(index);
            *plan = Plan::form(index, m, &self.held, &self.flexures);
        }
        let plan = &*plan;
        let guides = self.assemble_free(plan, k, ends, stiffness)?;
        let constraints = factor_free(plan, k, scaled, guides)?;
        // written in place: a pushed [Jet<8>; 3] is a call to memcpy
        moved.clear();
        moved.resize(cases.len() * bodies, [D::from(0.0); 3]);
        for (case, moved) in cases.iter().zip(moved.chunks_exact_mut(bodies.max(1))) {
            self.solve_case(case, plan, k, constraints.as_ref(), f, moved);
        }
        Ok(Solved {
            moved,
            references: &self.references,
            index: &plan.index,
            stiffness,
        })
    }

    /// The stiffness among the free degrees of freedom, numbered by `plan`, into the lower
    /// triangle of `k`: the flexures (each one's own stiffness into `stiffness`), the springs,
    /// and each guide as a spring; or the first flexure that joins a body to itself. Returns
    /// the guides' rows over the free degrees of freedom, for their [`Constraints`].
    fn assemble_free(
        &self,
        plan: &Plan,
        k: &mut Vec<D>,
        ends: &mut Vec<End<D>>,
        stiffness: &mut Vec<Stiffness<D>>,
    ) -> Result<Vec<Vec<(usize, D)>>, NetworkError> {
        let (index, m) = (&plan.index[..], plan.m);
        k.clear();
        k.resize(m * m, D::from(0.0));
        if ends.len() != 2 {
            ends.clear();
            ends.resize_with(2, End::zero);
        }
        if let Some(i) = self.flexures.iter().position(|fl| fl.from == fl.to) {
            return Err(NetworkError::SelfJoined { flexure: i });
        }
        // every flexure's slot is written below: zeroed only when the count changes
        if stiffness.len() != self.flexures.len() {
            stiffness.clear();
            stiffness.resize(self.flexures.len(), [D::from(0.0); 4]);
        }
        for (i, (fl, kf)) in self.flexures.iter().zip(stiffness.iter_mut()).enumerate() {
            self.add_flexure_free(fl, index, k, ends, plan.terms(i), kf);
        }
        for s in &self.springs {
            let a = along_row(&s.point, &self.references[s.body], &s.direction);
            add_spring(k, index, m, s.body, a, s.stiffness);
        }
        // each guide a spring as stiff as the stiffest free degree of freedom: any stiffness
        // gives the same constrained motion, and this one keeps the factor's conditioning
        let stiffest = (0..m).fold(0.0f64, |s, i| s.max(k[i * m + i].re().abs()));
        Ok(self
            .guides
            .iter()
            .map(|g| {
                let a = along_row(&g.point, &self.references[g.body], &g.direction);
                add_spring(
                    k,
                    index,
                    m,
                    g.body,
                    a,
                    D::from(stiffest.max(f64::MIN_POSITIVE)),
                );
                (0..3)
                    .filter(|&p| index[3 * g.body + p] != HELD)
                    .map(|p| (index[3 * g.body + p], a[p]))
                    .collect()
            })
            .collect())
    }

    /// One case's displacements into `moved`, its bodies' (a body not read NaN), from `k`
    /// factored: its loads gathered into `f` over the free degrees of freedom, numbered by
    /// `plan`, and substituted, then corrected by the guides' `constraints`.
    fn solve_case(
        &self,
        case: &Case<D>,
        plan: &Plan,
        k: &[D],
        constraints: Option<&Constraints<D>>,
        f: &mut Vec<D>,
        moved: &mut [[D; 3]],
    ) {
        let (index, m) = (&plan.index[..], plan.m);
        f.clear();
        f.resize(m, D::from(0.0));
        // the first entry of `f` loaded, and the first read: the forward substitution
        // starts at the one (the entries before stay zero), the back substitution ends
        // at the other (those before feed only entries not read)
        let mut loaded = m;
        let first_read = match case.read {
            None => 0,
            Some(read) => read
                .iter()
                .flat_map(|&b| &index[3 * b..3 * b + 3])
                .filter(|&&i| i != HELD)
                .fold(m, |a, &i| a.min(i)),
        };
        for l in case.loads.iter() {
            let origin = &self.references[l.body];
            let r = [l.point[0] - origin[0], l.point[1] - origin[1]];
            let o = 3 * l.body;
            let moment = l.moment + (r[0] * l.force[1] - r[1] * l.force[0]);
            // read in place: a list of the three (dof, value) pairs was a copy
            for (dof, v) in [(o, &l.force[0]), (o + 1, &l.force[1]), (o + 2, &moment)] {
                if index[dof] != HELD {
                    f[index[dof]] = f[index[dof]] + *v;
                    loaded = loaded.min(index[dof]);
                }
            }
        }
        match constraints {
            None => substitute(k, m, f, loaded, first_read),
            Some(c) => {
                // the correction reads the guided bodies and writes every entry
                substitute(k, m, f, loaded, 0);
                c.correct(f);
            }
        }
        for (b, (u, index)) in moved.iter_mut().zip(index.chunks_exact(3)).enumerate() {
            if case.read.is_some_and(|read| !read.contains(&b)) {
                *u = [D::from(f64::NAN); 3];
                continue;
            }
            for (v, &i) in u.iter_mut().zip(index) {
                if i != HELD {
                    *v = f[i];
                }
            }
        }
    }

    /// Each degree of freedom's place among those not held ([`HELD`] if held) into `index`,
    /// and their count.
    fn free_numbering(&self, index: &mut Vec<usize>) -> usize {
        index.clear();
        index.resize(3 * self.references.len(), 0);
        for &(body, dof) in &self.held {
            index[3 * body + dof as usize] = HELD;
        }
        let mut m = 0;
        for i in index.iter_mut().filter(|i| **i != HELD) {
            *i = m;
            m += 1;
        }
        m
    }

    /// Flexure `f`'s stiffness into the lower triangle of `k`, the free degrees of freedom
    /// numbered by `index`: each block `A_i^T K A_j` of the module's formula, with the maps'
    /// known zeros and ones skipped and each entry of the symmetric matrix formed once, by
    /// the flexure's [`Plan`] terms; and its own stiffness `K` into `stiffness` (written in
    /// place: returned, it was a `memcpy`).
    fn add_flexure_free(
        &self,
        f: &Flexure<D>,
        index: &[usize],
        k: &mut [D],
        ends: &mut [End<D>],
        terms: [&[Term]; 7],
        stiffness: &mut Stiffness<D>,
    ) {
        let c = &f.compliance;
        // K = C^-1: the axial entry, and the bending block's inverse, formed in its slot (formed
        // apart and then stored, the four were a `memcpy`)
        let det = c.c22 * c.c33 - c.c23 * c.c23;
        *stiffness = [c.c11.recip(), c.c33 / det, -(c.c23 / det), c.c22 / det];
        let [k11, k22, k23, k33] = &*stiffness;
        let (k11, k22, k23, k33) = (*k11, *k22, *k23, *k33);
        let (ex, ey) = (f.axis[0], f.axis[1]);
        // an end's map R T(r) from its body's reference motion to the end's motion in the
        // flexure's frame, by columns (u, v, theta); its third row is (0, 0, 1). The
        // clamped start's carries G (its v gains l theta) and enters with a minus sign.
        // Each end's map and K times it are written into the buffer's slot: an `End` (15
        // Jet<8>s) returned in an `Option` was copied twice. Only the columns of the degrees
        // of freedom not held are read, and formed.
        let end = |e: &mut End<D>, body: Body, point: &[D; 2], lever: Option<D>| {
            let Body::Rigid(b) = body else {
                e.body = None;
                return;
            };
            e.body = Some(b);
            let free = |q: usize| index[3 * b + q] != HELD;
            if free(0) {
                e.ka[0] = [k11 * ex, k22 * -ey, k23 * -ey];
            }
            if free(1) {
                e.ka[1] = [k11 * ey, k22 * ex, k23 * ex];
            }
            e.columns[0] = [ex, -ey];
            e.columns[1] = [ey, ex];
            if free(2) {
                let o = &self.references[b];
                let (rx, ry) = (point[0] - o[0], point[1] - o[1]);
                let t0 = ey * rx - ex * ry;
                let t1 = ey * ry + ex * rx;
                let t1 = match lever {
                    Some(l) => t1 + l,
                    None => t1,
                };
                e.ka[2] = [k11 * t0, k22 * t1 + k23, k23 * t1 + k33];
                e.columns[2] = [t0, t1];
            }
        };
        let (first, second) = ends.split_at_mut(1);
        end(&mut first[0], f.from, &f.start, Some(f.length));
        end(&mut second[0], f.to, &f.end, None);
        let ends: &[End<D>; 2] = (&*ends).try_into().expect("two ends");
        let dot = |t: &Term| dot(ends, t);
        let third = |t: &Term| ends[t.other & 1].ka[t.q.min(2)][2];
        let [pairs, same_moves, same, same_turn, across_moves, across, across_turn] = terms;
        // a translation's columns and `K A` are the same at both ends (`R`, and `K R`), so
        // each product of two translations is formed once for the flexure, bit for bit the
        // one each of its terms formed
        let mut moves = [[D::from(0.0); 2]; 2];
        for t in pairs {
            moves[t.p & 1][t.q & 1] = dot(t);
        }
        let moves = |t: &Term| moves[t.p & 1][t.q & 1];
        for t in same_moves {
            k[t.at] = k[t.at] + moves(t);
        }
        for t in same {
            k[t.at] = k[t.at] + dot(t);
        }
        for t in same_turn {
            k[t.at] = k[t.at] + (dot(t) + third(t));
        }
        for t in across_moves {
            k[t.at] = k[t.at] - moves(t);
        }
        for t in across {
            k[t.at] = k[t.at] - dot(t);
        }
        for t in across_turn {
            k[t.at] = k[t.at] - (dot(t) + third(t));
        }
    }
}

/// A spring to the ground along the row `a` of `body`'s reference motion ([`along_row`]),
/// `stiffness k a a^T`, into the lower triangle of `k`, the free degrees of freedom numbered
/// by `index` (`m` of them).
fn add_spring<D: Scalar>(
    k: &mut [D],
    index: &[usize],
    m: usize,
    body: usize,
    a: [D; 3],
    stiffness: D,
) {
    for p in 0..3 {
        for q in 0..=p {
            let (i, j) = (index[3 * body + p], index[3 * body + q]);
            if i != HELD && j != HELD {
                let (i, j) = (i.max(j), i.min(j));
                k[i * m + j] = k[i * m + j] + stiffness * a[p] * a[q];
            }
        }
    }
}

/// `k` factored in place ([`factor`]), a pivot that vanishes reported with its body and
/// direction; then the `guides`' [`Constraints`] on the factor (`None` without guides), or
/// the first guide that holds a motion already held.
fn factor_free<D: Scalar>(
    plan: &Plan,
    k: &mut [D],
    scaled: &mut Vec<D>,
    guides: Vec<Vec<(usize, D)>>,
) -> Result<Option<Constraints<D>>, NetworkError> {
    let (index, m) = (&plan.index[..], plan.m);
    factor(k, m, scaled).map_err(|free| {
        let dof = index.iter().position(|&i| i == free).unwrap_or(0);
        NetworkError::Free {
            body: dof / 3,
            direction: ["x", "y", "rotation"][dof % 3],
        }
    })?;
    if guides.is_empty() {
        return Ok(None);
    }
    let factored: &[D] = k;
    let solve = |f: &mut [D]| substitute(factored, m, f, 0, 0);
    Constraints::new(guides, m, solve)
        .map(Some)
        .map_err(|guide| NetworkError::Redundant { guide })
}

/// Term `t`'s `columns[p] . ka[q]`, the third row of `A` (0, 0, 1) left out. Inlined, its
/// indices masked to the arrays' sizes: a call per term, with its bounds checks, cost
/// about as much as the term's arithmetic.
#[inline(always)]
fn dot<D: Scalar>(ends: &[End<D>; 2], t: &Term) -> D {
    let a = &ends[t.one & 1].columns[t.p.min(2)];
    let kq = &ends[t.other & 1].ka[t.q.min(2)];
    a[0] * kq[0] + a[1] * kq[1]
}

/// Each flexure's terms of the stiffness among the free degrees of freedom: which of its
/// ends' columns meet in which entry of the lower triangle. They follow from the structure
/// alone (the free numbering, the bodies each flexure joins), so they are formed once for
/// a structure, not tested entry by entry at each design: those tests, on loops of zero to
/// three trips, were the assembly's unpredictable branches.
#[derive(Debug, Clone, Default)]
pub(super) struct Plan {
    /// The structure the terms are for: its bodies' count, the degrees of freedom held,
    /// and the free numbering they give ([`Network::free_numbering`]), `m` of them free.
    count: usize,
    held: Vec<(usize, Dof)>,
    index: Vec<usize>,
    m: usize,
    bodies: Vec<(Body, Body)>,
    terms: Vec<Term>,
    /// Flexure `i`'s terms in seven groups, `terms[groups[i][g]..groups[i][g + 1]]`: the
    /// distinct pairs `(p, q)` of two translations among its terms (each once, `at`
    /// unused); then an end with itself (added): two translations, the others, the end's
    /// rotation as `p` (added with `K`'s third row); then one end with the other
    /// (subtracted), in the same three groups.
    groups: Vec<[usize; 8]>,
}

/// Entry `at` of the stiffness gains `columns[p] . ka[q]` of ends `one` and `other`
/// ([`End`]; end 0 on `from`, 1 on `to`).
#[derive(Debug, Clone, Copy)]
struct Term {
    at: usize,
    one: usize,
    p: usize,
    other: usize,
    q: usize,
}

impl Plan {
    fn fits<D>(&self, count: usize, held: &[(usize, Dof)], flexures: &[Flexure<D>]) -> bool {
        self.count == count
            && self.held == held
            && self.bodies.len() == flexures.len()
            && self
                .bodies
                .iter()
                .zip(flexures)
                .all(|(&(from, to), f)| from == f.from && to == f.to)
    }

    fn form<D>(index: &[usize], m: usize, held: &[(usize, Dof)], flexures: &[Flexure<D>]) -> Plan {
        let mut plan = Plan {
            count: index.len() / 3,
            held: held.to_vec(),
            index: index.to_vec(),
            m,
            bodies: flexures.iter().map(|f| (f.from, f.to)).collect(),
            terms: Vec::new(),
            groups: Vec::with_capacity(flexures.len()),
        };
        for f in flexures {
            let mut groups: [Vec<Term>; 7] = Default::default();
            let ends = [f.from, f.to];
            for (one, bi) in ends.iter().enumerate() {
                let Body::Rigid(bi) = *bi else { continue };
                for (other, bj) in ends.iter().enumerate() {
                    let Body::Rigid(bj) = *bj else { continue };
                    for p in 0..3 {
                        let gi = index[3 * bi + p];
                        if gi == HELD {
                            continue;
                        }
                        for q in 0..3 {
                            let gj = index[3 * bj + q];
                            if gj == HELD || gj > gi {
                                continue;
                            }
                            let term = Term {
                                at: gi * m + gj,
                                one,
                                p,
                                other,
                                q,
                            };
                            let moves = p < 2 && q < 2;
                            if moves && !groups[0].iter().any(|t| (t.p, t.q) == (p, q)) {
                                groups[0].push(term);
                            }
                            let kind = if moves {
                                0
                            } else if p == 2 {
                                2
                            } else {
                                1
                            };
                            groups[1 + 3 * usize::from(one != other) + kind].push(term);
                        }
                    }
                }
            }
            let mut bounds = [plan.terms.len(); 8];
            for (g, terms) in groups.into_iter().enumerate() {
                plan.terms.extend(terms);
                bounds[g + 1] = plan.terms.len();
            }
            plan.groups.push(bounds);
        }
        plan
    }

    /// Flexure `i`'s seven groups of terms. Inlined: called, the seven slices cost about a
    /// hundred instructions a flexure.
    #[inline(always)]
    fn terms(&self, i: usize) -> [&[Term]; 7] {
        let g = &self.groups[i];
        std::array::from_fn(|j| &self.terms[g[j]..g[j + 1]])
    }
}

/// A flexure's end on a body: the body, the map `A` from its reference motion to the end's
/// motion in the flexure's frame by columns (the third row `(0, 0, 1)` left out), and the
/// flexure's stiffness times it, `K A`, by columns.
/// `body` is `None` on the ground; the columns of a held degree of freedom are stale.
#[derive(Debug, Clone)]
pub(super) struct End<D> {
    body: Option<usize>,
    columns: [[D; 2]; 3],
    ka: [[D; 3]; 3],
}

impl<D: Scalar> End<D> {
    fn zero() -> Self {
        let zero = D::from(0.0);
        End {
            body: None,
            columns: [[zero; 2]; 3],
            ka: [[zero; 3]; 3],
        }
    }
}

/// [`Network::free_numbering`]'s mark of a held degree of freedom.
pub(super) const HELD: usize = usize::MAX;

/// The row `T(P - O)^T n` that gives the motion of `point` along the unit `direction` from
/// its body's reference motion (its reference point `reference`).
fn along_row<D: Scalar>(point: &[D; 2], reference: &[D; 2], direction: &[D; 2]) -> [D; 3] {
    let r = [point[0] - reference[0], point[1] - reference[1]];
    let [nx, ny] = *direction;
    [nx, ny, -r[1] * nx + r[0] * ny]
}

/// A pivot below this fraction of the largest diagonal entry is a free motion. The
/// stiffest and softest directions of a flexure network differ by about the ratio of a
/// hinge's axial to its rotational stiffness over a lever squared (1e6 to 1e9 for
/// notches of 0.1 to 1 mm over links of 10 mm); a free motion leaves round-off, 1e-16 of
/// the diagonal.
const FREE_PIVOT: f64 = 1e-13;

/// `L D L^T` of the symmetric `k` in place (`L` below the diagonal, `D` on it; the upper
/// triangle is not read), or the first pivot that vanishes. Row `j` and each row below it
/// are read as slices, whose entries are read in place: indexed into the whole matrix,
/// every `Jet<8>` term was a bounds check and a copy, about a third of the factor's count.
/// Row `j` times the pivots, `w_p = L_jp D_p`, is formed once into `scaled` for the pivot
/// and every row below (Golub and Van Loan, "Matrix Computations", 3rd ed., Johns Hopkins
/// 1996, Sec. 4.1.2, Alg. 4.1.2): each term one product, where `L_ip L_jp D_p` was two.
fn factor<D: Scalar>(k: &mut [D], n: usize, scaled: &mut Vec<D>) -> Result<(), usize> {
    let scale = (0..n).map(|i| k[i * n + i].re().abs()).fold(0.0, f64::max);
    scaled.clear();
    scaled.resize(n, D::from(0.0));
    for j in 0..n {
        let (above, rest) = k.split_at_mut(j * n);
        let (row_j, below) = rest.split_at_mut(n);
        let w = &mut scaled[..j];
        let mut d = row_j[j];
        for (p, (w, l)) in w.iter_mut().zip(&row_j[..j]).enumerate() {
            *w = *l * above[p * n + p];
            d = d - *l * *w;
        }
        if d.re().is_nan() || d.re() <= FREE_PIVOT * scale {
            return Err(j);
        }
        row_j[j] = d;
        let w = &scaled[..j];
        for row_i in below.chunks_exact_mut(n) {
            let mut s = row_i[j];
            for (a, b) in row_i[..j].iter().zip(w) {
                s = s - *a * *b;
            }
            row_i[j] = s / d;
        }
    }
    Ok(())
}

/// `x` overwritten by `K^-1 x` from entry `from` on, `l` the factor of [`factor`], where
/// the entries of `x` before `loaded` are zero: `L^-1` keeps them zero, and the terms they
/// give are skipped (the same numbers: `a - l 0` is `a`); the entries before `from` are
/// left unfinished (the back substitution's last rows, which no entry from `from` on reads).
fn substitute<D: Scalar>(l: &[D], n: usize, x: &mut [D], loaded: usize, from: usize) {
    // each entry summed in a local from slices, in the same order as by index
    for i in loaded..n {
        let (done, rest) = x.split_at_mut(i);
        let mut xi = rest[0];
        for (a, b) in l[i * n + loaded..i * n + i].iter().zip(&done[loaded..]) {
            xi = xi - *a * *b;
        }
        rest[0] = xi;
    }
    for i in loaded.max(from)..n {
        x[i] = x[i] / l[i * n + i];
    }
    for i in (from..n).rev() {
        let (head, tail) = x.split_at_mut(i + 1);
        let mut xi = head[i];
        // column i of L below row i (none below the last)
        let column = l.get((i + 1) * n + i..).unwrap_or_default();
        for (a, b) in column.iter().step_by(n).zip(tail.iter()) {
            xi = xi - *a * *b;
        }
        head[i] = xi;
    }
}
