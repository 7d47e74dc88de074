//! A regular grid of points as a reference (`docs/math.md §12`): an OBJ
//! file whose faces are all quadrilaterals forming one `rows × cols` grid,
//! as a subdivided plane from Blender or Rhino is exported, made a surface
//! by the B-spline fit of `docs/math.md §10` through its points.
//!
//! The OBJ text is read by `tobj`; the grid is found from the faces alone:
//! a corner (a vertex of one quad) starts the first row, which runs along
//! the border to the next corner, and every next row is the one neighbour
//! of each vertex that is in neither the row nor the row before. Then every
//! quad must be one cell of that grid and every vertex used. The grid's
//! columns are the surface's `u`, its rows `v`; the parameters are the
//! chord lengths averaged over the rows and over the columns (*The NURBS
//! Book*, Eq. 9.5–9.6), and the surface is the bicubic B-spline through
//! every point: as many poles as points, knots by averaging (Eq. 9.8), the
//! least-squares fit of `docs/math.md §10` on those knots (a square system,
//! so an interpolation). OBJ states no unit: its lengths are taken as
//! metres.

use crate::error::{MAX_POINTS, ReferenceError};
use crate::geom;
use crate::mesh;
use crate::{FaceData, SurfaceKind};
use std::collections::HashMap;
use std::path::Path;
use streamline_kernel::DVec3;
use streamline_kernel::grid::Grid;
use streamline_kernel::nurbs::rational::NurbsSurface;
use streamline_kernel::nurbs::{KnotVector, Samples, fit_knots};

/// The fewest points a grid needs in each direction (a bicubic fit).
pub const MIN_GRID_SIDE: usize = 4;

/// What a grid file gives: its unit and its one face.
pub(crate) struct GridFile {
    pub unit: String,
    pub metres_per_unit: f64,
    pub faces: Vec<FaceData>,
}

/// The 1-based line of each `f` statement, in order.
fn face_lines(text: &str) -> Vec<usize> {
    text.lines()
        .enumerate()
        .filter(|(_, l)| {
            let t = l.trim_start();
            t.starts_with("f ") || t.starts_with("f\t")
        })
        .map(|(i, _)| i + 1)
        .collect()
}

/// Reads an OBJ point grid.
pub(crate) fn read(path: &Path, bytes: &[u8]) -> Result<GridFile, ReferenceError> {
    let text = String::from_utf8_lossy(bytes);
    let lines = face_lines(&text);
    let opts = tobj::LoadOptions {
        triangulate: false,
        single_index: false,
        ignore_points: true,
        ignore_lines: true,
    };
    let (models, _) = tobj::load_obj_buf(&mut text.as_bytes(), &opts, |_| {
        Err(tobj::LoadError::OpenFileFailed)
    })
    .map_err(|e| {
        ReferenceError::whole(
            path,
            format!("is not a readable OBJ file ({e}); check its `v` and `f` lines"),
        )
    })?;
    // one vertex list and one face list over every object
    let mut positions: Vec<DVec3> = Vec::new();
    let mut polygons: Vec<(Vec<usize>, usize)> = Vec::new();
    let line_of = |k: usize| lines.get(k).copied().unwrap_or(1);
    for m in &models {
        let mesh = &m.mesh;
        let base = positions.len();
        if base + mesh.positions.len() / 3 > MAX_POINTS {
            return Err(ReferenceError::whole(
                path,
                format!(
                    "the file has more than {MAX_POINTS} vertices, more than a reference is read with; decimate it"
                ),
            ));
        }
        for p in mesh.positions.chunks_exact(3) {
            let v = DVec3::new(p[0], p[1], p[2]);
            if !v.is_finite() {
                return Err(ReferenceError::whole(
                    path,
                    format!(
                        "vertex {} has a coordinate that is not a finite number; fix the `v` line",
                        positions.len() + 1
                    ),
                ));
            }
            positions.push(v);
        }
        let arities: Vec<u32> = if mesh.face_arities.is_empty() {
            vec![3; mesh.indices.len() / 3]
        } else {
            mesh.face_arities.clone()
        };
        let mut at = 0usize;
        for &n in &arities {
            let n = n as usize;
            let Some(idx) = mesh.indices.get(at..at + n) else {
                break;
            };
            polygons.push((
                idx.iter().map(|&i| base + i as usize).collect(),
                line_of(polygons.len()),
            ));
            at += n;
        }
    }
    if polygons.is_empty() {
        return Err(ReferenceError::whole(
            path,
            "has no faces; a point grid is an OBJ of quadrilateral faces (`f a b c d`), a mesh one of any faces",
        ));
    }
    // one grid of quads is a surface; anything else a mesh, which says why
    // it is not a grid when it is refused a fit
    let in_range = polygons
        .iter()
        .all(|(p, _)| p.iter().all(|&i| i < positions.len()));
    let not_grid = match polygons.iter().position(|(p, _)| p.len() != 4) {
        Some(k) => (
            polygons[k].1,
            format!("face {} has {} corners", k + 1, polygons[k].0.len()),
        ),
        None if !in_range => (0, "a face names a vertex past the end".to_string()),
        None => {
            let quads: Vec<[usize; 4]> = polygons
                .iter()
                .map(|(p, _)| [p[0], p[1], p[2], p[3]])
                .collect();
            match find_grid(&positions, &quads) {
                Ok(grid) => return grid_face(path, &positions, &grid, line_of(0)),
                Err((face, why)) => (face.map_or(0, line_of), why.replace("; ", ": ")),
            }
        }
    };
    Ok(GridFile {
        unit: "metre".into(),
        metres_per_unit: 1.0,
        faces: vec![mesh::from_obj(path, positions, &polygons, Some(not_grid))?],
    })
}

/// The face of the grid `grid` of vertex indices into `positions`: the
/// B-spline surface through its points.
fn grid_face(
    path: &Path,
    positions: &[DVec3],
    grid: &Grid<usize>,
    line: usize,
) -> Result<GridFile, ReferenceError> {
    let (rows, cols) = (grid.rows(), grid.cols());
    let points = Grid::new(
        rows,
        cols,
        grid.data().iter().map(|&i| positions[i]).collect(),
    )
    .map_err(|e| ReferenceError::whole(path, format!("{e}; re-export the grid")))?;
    let surface = fit_grid(&points).map_err(|why| ReferenceError::whole(path, why))?;
    let (area, bbox) = geom::area_and_bbox(&surface);
    if !area.is_finite() || bbox.iter().flatten().any(|x| !x.is_finite()) {
        return Err(ReferenceError::at(
            path,
            line,
            1,
            format!(
                "the surface through the grid of {rows} × {cols} points is too large to measure (its area overflows); write the file in a unit that keeps its coordinates below about 1e150"
            ),
        ));
    }
    Ok(GridFile {
        unit: "metre".into(),
        metres_per_unit: 1.0,
        faces: vec![FaceData {
            kind: SurfaceKind::Grid,
            entity: format!("a grid of {rows} × {cols} points"),
            line,
            surface: Some(surface),
            mesh: None,
            not_grid: None,
            closed: grid_closed(&points),
            trimmed: false,
            area,
            bbox: Some(bbox),
        }],
    })
}

/// Whether the grid's first and last columns (`u`), and rows (`v`), coincide.
fn grid_closed(points: &Grid<DVec3>) -> [bool; 2] {
    let (rows, cols) = (points.rows(), points.cols());
    let diag = geom::points_bbox(points.data().iter().copied())
        .map_or(0.0, |[lo, hi]| (DVec3::from(hi) - DVec3::from(lo)).length());
    let near = |a: DVec3, b: DVec3| a.distance(b) <= 1e-9 * diag;
    [
        (0..rows).all(|r| near(points.get(r, 0), points.get(r, cols - 1))),
        (0..cols).all(|c| near(points.get(0, c), points.get(rows - 1, c))),
    ]
}

/// The grid of vertex indices the quads form, or the face (0-based) and why not.
fn find_grid(
    positions: &[DVec3],
    faces: &[[usize; 4]],
) -> Result<Grid<usize>, (Option<usize>, String)> {
    let n = positions.len();
    let mut quads_of = vec![0u32; n];
    let mut neighbours: Vec<Vec<usize>> = vec![Vec::new(); n];
    let mut edges: HashMap<(usize, usize), u32> = HashMap::new();
    for (k, f) in faces.iter().enumerate() {
        for i in 0..4 {
            let (a, b) = (f[i], f[(i + 1) % 4]);
            if a == b || f.iter().filter(|&&x| x == a).count() > 1 {
                return Err((
                    Some(k),
                    format!(
                        "face {} repeats a vertex; remove it or fix its `f` line",
                        k + 1
                    ),
                ));
            }
            quads_of[a] += 1;
            let key = (a.min(b), a.max(b));
            let count = edges.entry(key).or_insert(0);
            *count += 1;
            if *count > 2 {
                return Err((
                    Some(k),
                    format!(
                        "face {} shares an edge with two other faces, so the faces are not one grid; export one grid of quads",
                        k + 1
                    ),
                ));
            }
            if *count == 1 {
                neighbours[a].push(b);
                neighbours[b].push(a);
            }
        }
    }
    let unused = (0..n).filter(|&v| quads_of[v] == 0).count();
    let corners: Vec<usize> = (0..n).filter(|&v| quads_of[v] == 1).collect();
    if corners.len() != 4 {
        return Err((
            None,
            format!(
                "the faces have {} corners (vertices of a single face), not the 4 of one rows × cols grid; export the points as one grid of quads",
                corners.len()
            ),
        ));
    }
    // the first row: from a corner along the border to the next corner
    let start = corners[0];
    let border = |v: usize, w: usize| edges.get(&(v.min(w), v.max(w))) == Some(&1);
    let first_step = neighbours[start]
        .iter()
        .copied()
        .find(|&w| border(start, w))
        .ok_or((
            None,
            "a corner has no border edge; export one grid of quads".to_string(),
        ))?;
    let mut row = vec![start, first_step];
    while quads_of[*row.last().unwrap_or(&start)] != 1 {
        let (prev, cur) = (row[row.len() - 2], row[row.len() - 1]);
        let next = neighbours[cur]
            .iter()
            .copied()
            .find(|&w| w != prev && border(cur, w) && !row.contains(&w));
        match next {
            Some(w) => row.push(w),
            None => {
                return Err((
                    None,
                    "the border of the faces does not run from corner to corner; export one grid of quads".into(),
                ));
            }
        }
        if row.len() > n {
            return Err((
                None,
                "the border of the faces does not close; export one grid of quads".into(),
            ));
        }
    }
    let cols = row.len();
    let used = n - unused;
    if cols < 2 || !used.is_multiple_of(cols) {
        return Err((
            None,
            format!("{used} vertices do not make rows of {cols}; export one grid of quads"),
        ));
    }
    let rows = used / cols;
    let mut grid = row.clone();
    let mut before: Vec<usize> = Vec::new();
    for _ in 1..rows {
        let mut next = Vec::with_capacity(cols);
        for (i, &v) in row.iter().enumerate() {
            let up: Vec<usize> = neighbours[v]
                .iter()
                .copied()
                .filter(|w| !row.contains(w) && !before.contains(w))
                .collect();
            match up.as_slice() {
                [w] => next.push(*w),
                _ => {
                    return Err((
                        None,
                        format!(
                            "vertex {} (row {}, column {}) does not have one neighbour in the next row, so the faces are not one grid; export one grid of quads",
                            v + 1,
                            grid.len() / cols + 1,
                            i + 1
                        ),
                    ));
                }
            }
        }
        grid.extend_from_slice(&next);
        before = std::mem::replace(&mut row, next);
    }
    // every quad is a cell, every used vertex once
    let mut seen = vec![false; n];
    for &v in &grid {
        if std::mem::replace(&mut seen[v], true) {
            return Err((
                None,
                format!(
                    "vertex {} is in the grid twice; export one grid of quads",
                    v + 1
                ),
            ));
        }
    }
    if faces.len() != (rows - 1) * (cols - 1) {
        return Err((
            None,
            format!(
                "{} faces for a {rows} × {cols} grid of points, which has {} cells; export one grid of quads",
                faces.len(),
                (rows - 1) * (cols - 1)
            ),
        ));
    }
    let mut cell_of: HashMap<[usize; 4], ()> = HashMap::new();
    for r in 0..rows - 1 {
        for c in 0..cols - 1 {
            let mut k = [
                grid[r * cols + c],
                grid[r * cols + c + 1],
                grid[(r + 1) * cols + c + 1],
                grid[(r + 1) * cols + c],
            ];
            k.sort_unstable();
            cell_of.insert(k, ());
        }
    }
    for (k, f) in faces.iter().enumerate() {
        let mut key = *f;
        key.sort_unstable();
        if !cell_of.contains_key(&key) {
            return Err((
                Some(k),
                format!(
                    "face {} is not a cell of the {rows} × {cols} grid; export one grid of quads",
                    k + 1
                ),
            ));
        }
    }
    if rows < MIN_GRID_SIDE || cols < MIN_GRID_SIDE {
        return Err((
            None,
            format!(
                "the grid has {rows} × {cols} points; a surface is fitted through at least {MIN_GRID_SIDE} × {MIN_GRID_SIDE}: subdivide the grid"
            ),
        ));
    }
    Grid::new(rows, cols, grid).map_err(|e| (None, e.to_string()))
}

/// Chord-length parameters of a sequence of rows, averaged over them.
fn averaged(lines: &[Vec<DVec3>]) -> Result<Vec<f64>, String> {
    let m = lines.first().map_or(0, Vec::len);
    let mut acc = vec![0.0; m];
    let mut used = 0.0;
    for line in lines {
        let total: f64 = line.windows(2).map(|w| w[0].distance(w[1])).sum();
        if total <= 0.0 || !total.is_finite() {
            continue;
        }
        let mut s = 0.0;
        for (i, w) in line.windows(2).enumerate() {
            s += w[0].distance(w[1]);
            acc[i + 1] += s / total;
        }
        used += 1.0;
    }
    if used == 0.0 {
        return Err("every row of the grid has zero length; the points coincide".into());
    }
    let mut t: Vec<f64> = acc.iter().map(|a| a / used).collect();
    t[0] = 0.0;
    if let Some(l) = t.last_mut() {
        *l = 1.0;
    }
    Ok(t)
}

/// The bicubic B-spline through the grid's points, as a NURBS surface.
fn fit_grid(points: &Grid<DVec3>) -> Result<NurbsSurface, String> {
    let (rows, cols) = (points.rows(), points.cols());
    let row_lines: Vec<Vec<DVec3>> = (0..rows)
        .map(|r| (0..cols).map(|c| points.get(r, c)).collect())
        .collect();
    let col_lines: Vec<Vec<DVec3>> = (0..cols)
        .map(|c| (0..rows).map(|r| points.get(r, c)).collect())
        .collect();
    let u = averaged(&row_lines)?;
    let v = averaged(&col_lines)?;
    let (ku, kv) = (averaged_knots(&u)?, averaged_knots(&v)?);
    let samples = Samples::new(points.clone(), u, v).map_err(|e| {
        format!("the grid's points cannot be fitted ({e}); check for repeated points")
    })?;
    let f = fit_knots(&samples, &ku, &kv).map_err(|e| {
        format!("no B-spline surface passes through the grid's points ({e}); check the grid for folds or repeated points")
    })?;
    Ok(NurbsSurface::from_bspline(&f))
}

/// The cubic knots of interpolation at `params` by averaging (*The NURBS
/// Book*, Eq. 9.8): as many poles as points, so the least-squares fit on
/// them passes through every point.
fn averaged_knots(params: &[f64]) -> Result<KnotVector, String> {
    let p = 3;
    let n = params.len();
    let interior: Vec<f64> = (1..n.saturating_sub(p))
        .map(|j| params[j..j + p].iter().sum::<f64>() / p as f64)
        .collect();
    KnotVector::with_interior(p, &interior).ok_or_else(|| {
        "the grid's points are too close together to fit through; remove repeated points"
            .to_string()
    })
}
