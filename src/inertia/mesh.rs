//! Bodies from simplicial meshes: the volume, first and second moments of each simplex from
//! the vertex formula, summed without allocating per simplex.

use super::InertiaError;
use super::body::Body;
use super::tolerance::{DEGENERACY_TOLERANCE, MASS_TENSOR_TOLERANCE};
use super::validate::{check_dim, check_points, check_positive, sorted_eigen, symmetrize};
use crate::numeric::determinant;
use nalgebra::{DMatrix, DVector};
use smallvec::SmallVec;

/// How the simplices of a mesh are combined by [`Body::simplicial_mesh`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SimplexOrientation {
    /// Each simplex contributes with the sign of det[v₁ − v₀, …, v_N − v₀].
    ///
    /// Use this for consistently oriented meshes: a tiling whose simplices all have the same
    /// orientation, or cones over a closed, consistently oriented boundary, which may be
    /// non-convex and whose apex may lie outside (ten Bosch, *N-Dimensional Rigid Body Dynamics*, 2020). If the
    /// total comes out negative, the whole mesh is taken with the opposite orientation.
    Signed,
    /// Each simplex contributes its absolute volume.
    ///
    /// Use this for a tiling (simplices that do not overlap) listed in arbitrary vertex
    /// order, such as the Kuhn triangulation of a cube.
    Unsigned,
}

impl Body {
    /// Returns the uniform-density body filling a mesh of N-simplices.
    ///
    /// # Accepted format
    /// - `vertices`: points in ℝᴺ, all of the same length N ≥ 1.
    /// - `simplices`: one entry per N-simplex, each listing N+1 distinct 0-based indices into
    ///   `vertices`. The order of the indices fixes the orientation sign of
    ///   det[v₁ − v₀, …, v_N − v₀].
    /// - `orientation`: [`SimplexOrientation::Signed`] sums signed contributions (a tiling
    ///   with one orientation, or cones over a closed consistently oriented boundary, as in
    ///   ten Bosch 2020; a negative total is flipped); [`SimplexOrientation::Unsigned`] sums
    ///   absolute contributions (a non-overlapping tiling in any vertex order).
    ///
    /// Simplices of zero volume are allowed and contribute nothing. Each simplex
    /// contributes its volume, first moment and second moment from the vertex formula
    ///, all taken about the vertex mean for accuracy; then
    /// c = ∫x dV / V and J = ρ (∫ x xᵀ dV − V c cᵀ).
    ///
    /// # Errors
    /// [`InertiaError::Empty`], [`InertiaError::LengthMismatch`], [`InertiaError::NonFinite`],
    /// [`InertiaError::NotPositive`] (density), [`InertiaError::WrongSimplexSize`],
    /// [`InertiaError::VertexIndexOutOfRange`], [`InertiaError::ZeroMeshVolume`] when the
    /// (signed) volumes cancel, [`InertiaError::InconsistentMesh`] when the result has a
    /// clearly negative second moment.
    pub fn simplicial_mesh<S: AsRef<[usize]>>(
        vertices: &[DVector<f64>],
        simplices: &[S],
        density: f64,
        orientation: SimplexOrientation,
    ) -> Result<Body, InertiaError> {
        let dim = check_points("vertices", vertices)?;
        check_positive("density", None, density)?;
        if simplices.is_empty() {
            return Err(InertiaError::Empty {
                quantity: "simplices",
            });
        }
        for (s, simplex) in simplices.iter().enumerate() {
            check_indices(s, simplex.as_ref(), dim + 1, vertices.len())?;
        }
        let reference =
            vertices.iter().fold(DVector::zeros(dim), |acc, v| acc + v) / vertices.len() as f64;
        // One flat buffer of shifted vertices: no allocation per vertex or per simplex.
        let mut local = Vec::with_capacity(dim * vertices.len());
        for v in vertices {
            local.extend(v.iter().zip(reference.iter()).map(|(a, b)| a - b));
        }
        if (2..=8).contains(&dim) {
            let mut acc = MeshAccumulator::new(dim);
            for simplex in simplices {
                acc.add_indexed(&local, simplex.as_ref(), orientation);
            }
            return finish_mesh(dim, &reference, acc, density);
        }
        mesh_body(
            dim,
            &reference,
            simplices.iter().map(|s| {
                s.as_ref()
                    .iter()
                    .map(|&k| &local[k * dim..(k + 1) * dim])
                    .collect::<SmallVec<[&[f64]; 9]>>()
            }),
            density,
            orientation,
        )
    }

    /// Returns the uniform-density solid bounded by a closed, consistently oriented boundary
    /// mesh of (N−1)-simplices (ten Bosch, *N-Dimensional Rigid Body Dynamics*, 2020).
    ///
    /// Each facet lists N vertex indices. The solid is the signed sum of the cones from the
    /// vertex mean (the apex) to each facet, so the solid may be non-convex and the apex may
    /// lie outside it. Facets are consistently oriented when each (N−2)-face is shared by two
    /// facets that induce opposite orientations on it (for N = 2: the polygon's edges
    /// (a, b) all run the same way round). Either global orientation is accepted.
    ///
    /// Orientation is checked by vertex index: wherever an (N−2)-face is shared by exactly
    /// two facets, they must induce opposite orientations on it. A flipped facet (one listed
    /// in the wrong vertex order) would otherwise subtract its cone instead of adding it and
    /// silently change the volume, so it is refused with
    /// [`InertiaError::InconsistentOrientation`], which names it (the facet on the minority
    /// side of its connected component).
    ///
    /// Closedness is not checked (facets may use separate copies of coincident vertices, so
    /// an index-based check would reject valid input; faces shared by a number of facets
    /// other than two are not checked either). An open boundary yields the signed sum of its
    /// cones; it is reported only when that sum has zero volume
    /// ([`InertiaError::ZeroMeshVolume`]) or a negative second moment
    /// ([`InertiaError::InconsistentMesh`]).
    ///
    /// # Errors
    /// As [`Body::simplicial_mesh`], with facets of N indices; N ≥ 2 is required
    /// ([`InertiaError::DimensionTooSmall`]); [`InertiaError::InconsistentOrientation`] for a
    /// flipped facet.
    pub fn closed_boundary_mesh<S: AsRef<[usize]>>(
        vertices: &[DVector<f64>],
        facets: &[S],
        density: f64,
    ) -> Result<Body, InertiaError> {
        let dim = check_points("vertices", vertices)?;
        check_dim(dim, 2)?;
        check_positive("density", None, density)?;
        if facets.is_empty() {
            return Err(InertiaError::Empty { quantity: "facets" });
        }
        for (s, facet) in facets.iter().enumerate() {
            check_indices(s, facet.as_ref(), dim, vertices.len())?;
        }
        check_facet_orientation(facets)?;
        let reference =
            vertices.iter().fold(DVector::zeros(dim), |acc, v| acc + v) / vertices.len() as f64;
        let local: Vec<DVector<f64>> = vertices.iter().map(|v| v - &reference).collect();
        let apex = DVector::zeros(dim);
        mesh_body(
            dim,
            &reference,
            facets.iter().map(|f| {
                std::iter::once(apex.as_slice())
                    .chain(f.as_ref().iter().map(|&k| local[k].as_slice()))
                    .collect::<SmallVec<[&[f64]; 9]>>()
            }),
            density,
            SimplexOrientation::Signed,
        )
    }
}

fn factorial(n: usize) -> f64 {
    (1..=n).fold(1.0, |acc, k| acc * k as f64)
}

/// Signed volume, first moment ∫ x dV and second moment ∫ x xᵀ dV of the simplex with the
/// given vertices (already relative to the reference point), all with the sign of
/// det[w₁ − w₀, …, w_N − w₀]. Also returns the relative volume |det| / Π|edges|.
///
/// Formulas: Vol = det/N!, ∫x dV = Vol s/(N+1), ∫ x xᵀ dV = Vol/((N+1)(N+2)) (Σ w wᵀ + s sᵀ)
/// with s = Σ wₖ.
pub(super) fn simplex_moments(w: &[&DVector<f64>]) -> (f64, DVector<f64>, DMatrix<f64>, f64) {
    let n = w.len() - 1;
    let mut edges = DMatrix::zeros(n, n);
    let mut edge_product = 1.0;
    for k in 1..=n {
        let e = w[k] - w[0];
        edge_product *= e.norm();
        edges.set_column(k - 1, &e);
    }
    let det = edges.lu().determinant();
    let relative = if edge_product > 0.0 {
        det.abs() / edge_product
    } else {
        0.0
    };
    let volume = det / factorial(n);
    let mut s = DVector::zeros(n);
    let mut second = DMatrix::zeros(n, n);
    for v in w {
        s += *v;
        second.ger(1.0, v, v, 1.0);
    }
    second.ger(1.0, &s, &s, 1.0);
    let nf = n as f64;
    let first = &s * (volume / (nf + 1.0));
    let second = second * (volume / ((nf + 1.0) * (nf + 2.0)));
    (volume, first, second, relative)
}

fn check_indices(
    simplex: usize,
    indices: &[usize],
    expected: usize,
    vertex_count: usize,
) -> Result<(), InertiaError> {
    let found = indices.len();
    if found != expected {
        return Err(InertiaError::WrongSimplexSize {
            simplex,
            expected,
            found,
        });
    }
    match indices.iter().find(|&&k| k >= vertex_count) {
        Some(&vertex) => Err(InertiaError::VertexIndexOutOfRange {
            simplex,
            vertex,
            vertex_count,
        }),
        None => Ok(()),
    }
}

/// Sums simplex contributions (vertices relative to `reference`) into a body.
fn mesh_body<'a, I>(
    dim: usize,
    reference: &DVector<f64>,
    simplices: I,
    density: f64,
    orientation: SimplexOrientation,
) -> Result<Body, InertiaError>
where
    I: Iterator<Item = SmallVec<[&'a [f64]; 9]>>,
{
    let mut acc = MeshAccumulator::new(dim);
    for vertices in simplices {
        acc.add(&vertices, orientation);
    }
    finish_mesh(dim, reference, acc, density)
}

/// Turns accumulated simplex moments into a body (shift to the centre of mass, checks).
fn finish_mesh(
    dim: usize,
    reference: &DVector<f64>,
    acc: MeshAccumulator,
    density: f64,
) -> Result<Body, InertiaError> {
    let (mut volume, unsigned, mut first, mut second) = acc.finish();
    if !volume.is_finite() || volume.abs() <= DEGENERACY_TOLERANCE * unsigned {
        return Err(InertiaError::ZeroMeshVolume {
            signed_volume: volume,
            unsigned_volume: unsigned,
        });
    }
    if volume < 0.0 {
        volume = -volume;
        first = -first;
        second = -second;
    }
    let shift = &first / volume;
    let mut j = second;
    j.ger(-volume, &shift, &shift, 1.0);
    j *= density;
    let j = symmetrize(&j);
    let (values, _) = sorted_eigen(&j);
    let largest = values[dim - 1];
    if values[0] < -MASS_TENSOR_TOLERANCE * largest.abs() || largest <= 0.0 {
        return Err(InertiaError::InconsistentMesh {
            min_moment: values[0],
            max_moment: largest,
        });
    }
    Body::new_checked(density * volume, reference + shift, j, Some(volume))
}

/// Sums the signed volume, first and second moments of many simplices without allocating
/// per simplex (stack scratch for N ≤ 16): the hot loop of mesh inertia.
///
/// Per simplex with vertices w₀ … w_N (relative to the reference point): Vol = det/N!,
/// ∫x dV = Vol s/(N+1), ∫x xᵀ dV = Vol/((N+1)(N+2)) (Σ w wᵀ + s sᵀ), s = Σ wₖ
/// (the vertex formula); only the upper triangle is accumulated.
struct MeshAccumulator {
    n: usize,
    inverse_factorial: f64,
    volume: f64,
    unsigned: f64,
    first: Vec<f64>,
    second: Vec<f64>,
}

impl MeshAccumulator {
    fn new(n: usize) -> Self {
        MeshAccumulator {
            n,
            inverse_factorial: 1.0 / factorial(n),
            volume: 0.0,
            unsigned: 0.0,
            first: vec![0.0; n],
            second: vec![0.0; n * n],
        }
    }

    fn add(&mut self, w: &[&[f64]], orientation: SimplexOrientation) {
        let n = self.n;
        if n > 16 {
            let owned: Vec<DVector<f64>> =
                w.iter().map(|v| DVector::from_column_slice(v)).collect();
            let refs: Vec<&DVector<f64>> = owned.iter().collect();
            let (v, f, s, _) = simplex_moments(&refs);
            let sign = orientation_sign(orientation, v);
            self.volume += sign * v;
            self.unsigned += v.abs();
            for r in 0..n {
                self.first[r] += sign * f[r];
                for c in 0..n {
                    self.second[r * n + c] += sign * s[(r, c)];
                }
            }
            return;
        }
        match n {
            2 => return self.add_fixed::<2>(w, orientation),
            3 => return self.add_fixed::<3>(w, orientation),
            4 => return self.add_fixed::<4>(w, orientation),
            5 => return self.add_fixed::<5>(w, orientation),
            6 => return self.add_fixed::<6>(w, orientation),
            7 => return self.add_fixed::<7>(w, orientation),
            8 => return self.add_fixed::<8>(w, orientation),
            _ => {}
        }
        let mut a = [0.0f64; 256];
        for k in 1..=n {
            for r in 0..n {
                a[r * n + (k - 1)] = w[k][r] - w[0][r];
            }
        }
        let volume = determinant(n, &mut a[..n * n]) * self.inverse_factorial;
        self.add_moments(volume, orientation, w, n);
    }

    /// Adds the volume and the first and second moments of the simplex with vertex rows
    /// `rows` (N + 1 of them, N ≤ 16) and determinant volume `volume`: with s the sum of the
    /// vertices and f the signed volume, ∫x dV = f s/(N + 1) and
    /// ∫x xᵀ dV = f (s sᵀ + Σ vᵢvᵢᵀ)/((N + 1)(N + 2)) (upper triangle).
    #[inline(always)]
    fn add_moments<V: AsRef<[f64]>>(
        &mut self,
        volume: f64,
        orientation: SimplexOrientation,
        rows: &[V],
        n: usize,
    ) {
        let sign = orientation_sign(orientation, volume);
        let f = sign * volume;
        self.volume += f;
        self.unsigned += volume.abs();
        let mut s = [0.0f64; 16];
        for v in rows {
            for (sr, x) in s.iter_mut().zip(&v.as_ref()[..n]) {
                *sr += x;
            }
        }
        let nf = n as f64;
        let c1 = f / (nf + 1.0);
        let c2 = f / ((nf + 1.0) * (nf + 2.0));
        for r in 0..n {
            self.first[r] += c1 * s[r];
            for c in r..n {
                let mut x = s[r] * s[c];
                for v in rows {
                    let v = v.as_ref();
                    x += v[r] * v[c];
                }
                self.second[r * n + c] += c2 * x;
            }
        }
    }

    /// Adds the simplex whose vertex `k` is `flat[idx[k]·N ..][..N]` (N = 2 … 8, indices
    /// already validated).
    fn add_indexed(&mut self, flat: &[f64], idx: &[usize], orientation: SimplexOrientation) {
        macro_rules! go {
            ($n:literal) => {{
                let mut v = [[0.0f64; $n]; 9];
                for (row, &k) in v.iter_mut().zip(idx) {
                    row.copy_from_slice(&flat[k * $n..(k + 1) * $n]);
                }
                self.add_rows::<$n>(&v, orientation)
            }};
        }
        match self.n {
            2 => go!(2),
            3 => go!(3),
            4 => go!(4),
            5 => go!(5),
            6 => go!(6),
            7 => go!(7),
            8 => go!(8),
            _ => unreachable!("add_indexed is only called for N = 2 … 8"),
        }
    }

    /// [`MeshAccumulator::add`] for a fixed N: stack arrays the compiler unrolls.
    fn add_fixed<const N: usize>(&mut self, w: &[&[f64]], orientation: SimplexOrientation) {
        let mut v = [[0.0f64; N]; 9];
        for (k, row) in v.iter_mut().enumerate().take(N + 1) {
            row.copy_from_slice(&w[k][..N]);
        }
        self.add_rows::<N>(&v, orientation);
    }

    /// Adds the simplex with vertex rows `v[0..=N]`.
    fn add_rows<const N: usize>(&mut self, v: &[[f64; N]; 9], orientation: SimplexOrientation) {
        let mut a = [[0.0f64; N]; N];
        for k in 1..=N {
            for r in 0..N {
                a[r][k - 1] = v[k][r] - v[0][r];
            }
        }
        // Gaussian elimination with partial pivoting.
        let mut det = 1.0;
        for col in 0..N {
            let mut pivot = col;
            for r in col + 1..N {
                if a[r][col].abs() > a[pivot][col].abs() {
                    pivot = r;
                }
            }
            if a[pivot][col] == 0.0 {
                det = 0.0;
                break;
            }
            if pivot != col {
                a.swap(col, pivot);
                det = -det;
            }
            let p = a[col][col];
            det *= p;
            let inv_p = 1.0 / p;
            let (top, bottom) = a.split_at_mut(col + 1);
            let pivot_row = &top[col];
            for row in bottom.iter_mut() {
                let factor = row[col] * inv_p;
                for (x, &q) in row[col + 1..].iter_mut().zip(&pivot_row[col + 1..]) {
                    *x -= factor * q;
                }
            }
        }
        let volume = det * self.inverse_factorial;
        self.add_moments(volume, orientation, &v[..=N], N);
    }

    /// Returns (signed volume, unsigned volume, ∫x dV, ∫x xᵀ dV).
    fn finish(self) -> (f64, f64, DVector<f64>, DMatrix<f64>) {
        let n = self.n;
        let mut second = DMatrix::from_row_slice(n, n, &self.second);
        if n <= 16 {
            for r in 0..n {
                for c in 0..r {
                    second[(r, c)] = second[(c, r)];
                }
            }
        }
        (
            self.volume,
            self.unsigned,
            DVector::from_vec(self.first),
            second,
        )
    }
}

fn orientation_sign(orientation: SimplexOrientation, volume: f64) -> f64 {
    match orientation {
        SimplexOrientation::Signed => 1.0,
        SimplexOrientation::Unsigned => {
            if volume < 0.0 {
                -1.0
            } else {
                1.0
            }
        }
    }
}

/// An (N−2)-face of a boundary mesh: its vertex indices, sorted.
type Face = SmallVec<[usize; 8]>;

/// Checks that facets sharing an (N−2)-face (by vertex index) induce opposite orientations on
/// it, and names a flipped facet otherwise.
///
/// Removing vertex k from a facet (v₀, …, v_(N−1)) leaves a face with induced orientation
/// (−1)ᵏ; written with sorted indices, it gains the sign of the sorting permutation. Two
/// facets agree across a face when these signs are opposite. Walking the facet adjacency
/// from each unvisited facet assigns every facet "kept" or "flipped" relative to the first
/// of its component; the smaller class is the one reported (a single flipped facet among
/// consistent neighbours is named exactly). Facets whose indices repeat a vertex have no
/// orientation and are skipped.
fn check_facet_orientation<S: AsRef<[usize]>>(facets: &[S]) -> Result<(), InertiaError> {
    use std::collections::HashMap;
    // face (sorted indices) -> list of (facet, induced sign)
    let mut faces: HashMap<Face, SmallVec<[(usize, i8); 2]>> = HashMap::new();
    for (f, facet) in facets.iter().enumerate() {
        let facet = facet.as_ref();
        let mut sorted: SmallVec<[usize; 8]> = SmallVec::from_slice(facet);
        sorted.sort_unstable();
        if sorted.windows(2).any(|w| w[0] == w[1]) {
            continue;
        }
        for k in 0..facet.len() {
            let mut face: Face = facet
                .iter()
                .enumerate()
                .filter(|&(i, _)| i != k)
                .map(|(_, &v)| v)
                .collect();
            let parity = sort_parity(&mut face);
            let sign = if (k % 2 == 0) == (parity > 0) { 1 } else { -1 };
            faces.entry(face).or_default().push((f, sign));
        }
    }
    // Adjacency through faces shared by exactly two facets: `same` = the two facets induce
    // the same sign there, so one of them is flipped relative to the other.
    let mut neighbours: Vec<Vec<(usize, bool, usize)>> = vec![Vec::new(); facets.len()];
    let mut face_list: Vec<Face> = Vec::new();
    // Sorted, so that the facet named in an error does not depend on hashing.
    let mut faces: Vec<_> = faces.into_iter().collect();
    faces.sort_unstable_by(|a, b| a.0.cmp(&b.0));
    for (face, users) in faces {
        if let [(a, sa), (b, sb)] = users[..]
            && a != b
        {
            let id = face_list.len();
            face_list.push(face);
            neighbours[a].push((b, sa == sb, id));
            neighbours[b].push((a, sa == sb, id));
        }
    }
    let mut flip: Vec<Option<bool>> = vec![None; facets.len()];
    for start in 0..facets.len() {
        if flip[start].is_some() {
            continue;
        }
        flip[start] = Some(false);
        let mut component = vec![start];
        let mut stack = vec![start];
        let mut contradiction = None;
        while let Some(f) = stack.pop() {
            let mine = flip[f].unwrap_or(false);
            for &(g, same, face) in &neighbours[f] {
                let wanted = mine ^ same;
                match flip[g] {
                    None => {
                        flip[g] = Some(wanted);
                        component.push(g);
                        stack.push(g);
                    }
                    Some(x) if x != wanted && contradiction.is_none() => {
                        contradiction = Some((g, f, face));
                    }
                    _ => {}
                }
            }
        }
        let flipped: Vec<usize> = component
            .iter()
            .copied()
            .filter(|&f| flip[f] == Some(true))
            .collect();
        let minority_is_flipped = 2 * flipped.len() <= component.len();
        let culprit = if let Some((g, _, _)) = contradiction {
            Some(g)
        } else if flipped.is_empty() {
            None
        } else if minority_is_flipped {
            flipped.iter().copied().min()
        } else {
            component
                .iter()
                .copied()
                .filter(|&f| flip[f] == Some(false))
                .min()
        };
        if let Some(facet) = culprit {
            // A neighbour that induces the same orientation on a shared face.
            let (neighbour, face) = neighbours[facet]
                .iter()
                .find(|&&(_, same, _)| same)
                .or(neighbours[facet].first())
                .map(|&(g, _, face)| (g, face_list[face].to_vec()))
                .unwrap_or((facet, Vec::new()));
            return Err(InertiaError::InconsistentOrientation {
                facet,
                neighbour,
                face,
            });
        }
    }
    Ok(())
}

/// Sorts `v` (distinct entries) and returns the sign of the sorting permutation.
fn sort_parity(v: &mut [usize]) -> i8 {
    let mut sign = 1;
    // Insertion sort: each swap is a transposition.
    for i in 1..v.len() {
        let mut j = i;
        while j > 0 && v[j - 1] > v[j] {
            v.swap(j - 1, j);
            sign = -sign;
            j -= 1;
        }
    }
    sign
}
