//! A dense row-major grid: `rows` streamlines (parameter `t`) × `cols` entries
//! along each streamline (parameter `s`).

use crate::error::KernelError;

/// A rectangular grid stored row by row.
#[derive(Debug, Clone, PartialEq)]
pub struct Grid<T> {
    rows: usize,
    cols: usize,
    data: Vec<T>,
}

impl<T: Copy> Grid<T> {
    /// A grid from row-major data; `data.len()` must be `rows * cols`.
    pub fn new(rows: usize, cols: usize, data: Vec<T>) -> Result<Self, KernelError> {
        if data.len() != rows * cols {
            return Err(KernelError::LengthMismatch {
                what: "grid data",
                got: data.len(),
                expected: rows * cols,
            });
        }
        Ok(Grid { rows, cols, data })
    }

    /// A grid filled with one value.
    pub fn filled(rows: usize, cols: usize, value: T) -> Self {
        Grid {
            rows,
            cols,
            data: vec![value; rows * cols],
        }
    }

    /// A grid from nested rows; rows of different lengths are an error naming the row.
    pub fn from_rows(rows: &[Vec<T>]) -> Result<Self, KernelError> {
        let cols = rows.first().map_or(0, Vec::len);
        let mut data = Vec::with_capacity(rows.len() * cols);
        for (r, row) in rows.iter().enumerate() {
            if row.len() != cols {
                return Err(KernelError::RaggedGrid {
                    row: r,
                    len: row.len(),
                    expected: cols,
                });
            }
            data.extend_from_slice(row);
        }
        Ok(Grid {
            rows: rows.len(),
            cols,
            data,
        })
    }

    /// Gives the grid the shape `rows × cols`, reusing its allocation; entries
    /// are left as they were (new ones are `fill`) for the caller to overwrite.
    pub(crate) fn reshape(&mut self, rows: usize, cols: usize, fill: T) {
        self.rows = rows;
        self.cols = cols;
        self.data.resize(rows * cols, fill);
    }

    /// The row-major data.
    pub fn into_data(self) -> Vec<T> {
        self.data
    }

    /// Number of rows (streamlines).
    pub fn rows(&self) -> usize {
        self.rows
    }

    /// Number of columns (entries per streamline).
    pub fn cols(&self) -> usize {
        self.cols
    }

    /// Entry at (`row`, `col`).
    #[inline]
    pub fn get(&self, row: usize, col: usize) -> T {
        self.data[row * self.cols + col]
    }

    /// Sets the entry at (`row`, `col`).
    #[inline]
    pub fn set(&mut self, row: usize, col: usize, value: T) {
        self.data[row * self.cols + col] = value;
    }

    /// One row.
    #[inline]
    pub fn row(&self, row: usize) -> &[T] {
        &self.data[row * self.cols..(row + 1) * self.cols]
    }

    /// One row, mutable.
    #[inline]
    pub fn row_mut(&mut self, row: usize) -> &mut [T] {
        &mut self.data[row * self.cols..(row + 1) * self.cols]
    }

    /// One column, copied.
    pub fn column(&self, col: usize) -> Vec<T> {
        (0..self.rows).map(|r| self.get(r, col)).collect()
    }

    /// All entries, row-major.
    pub fn data(&self) -> &[T] {
        &self.data
    }

    /// All entries, mutable.
    pub fn data_mut(&mut self) -> &mut [T] {
        &mut self.data
    }

    /// The transposed grid.
    pub fn transpose(&self) -> Self {
        let mut data = Vec::with_capacity(self.data.len());
        for c in 0..self.cols {
            for r in 0..self.rows {
                data.push(self.get(r, c));
            }
        }
        Grid {
            rows: self.cols,
            cols: self.rows,
            data,
        }
    }

    /// Reverses the order of rows.
    pub fn reverse_rows(&self) -> Self {
        let mut data = Vec::with_capacity(self.data.len());
        for r in (0..self.rows).rev() {
            data.extend_from_slice(self.row(r));
        }
        Grid {
            rows: self.rows,
            cols: self.cols,
            data,
        }
    }

    /// Reverses every row (the order of columns).
    pub fn reverse_cols(&self) -> Self {
        let mut g = self.clone();
        for r in 0..self.rows {
            g.row_mut(r).reverse();
        }
        g
    }

    /// Applies `f` to every entry.
    pub fn map<U: Copy>(&self, f: impl FnMut(T) -> U) -> Grid<U> {
        Grid {
            rows: self.rows,
            cols: self.cols,
            data: self.data.iter().copied().map(f).collect(),
        }
    }
}
