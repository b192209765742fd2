//! The ASCII-grid shortcut for cell mazes (`[grid]` in a world file): parsing the drawing into
//! cell walls, and turning cell walls into merged wall boxes.

use super::geometry::WallBox;

/// A cell maze: which cell edges carry a wall.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CellMaze {
    /// Number of cell rows (north to south in the drawing).
    pub rows: usize,
    /// Number of cell columns (west to east).
    pub cols: usize,
    /// `horizontal[k * cols + c]`: a wall on grid line k (0 = north edge) above cell column c;
    /// `(rows + 1) * cols` entries.
    pub horizontal: Vec<bool>,
    /// `vertical[r * (cols + 1) + k]`: a wall on grid line k (0 = west edge) beside cell row r;
    /// `rows * (cols + 1)` entries.
    pub vertical: Vec<bool>,
    /// Cell (column, row) marked `S`.
    pub start: Option<(usize, usize)>,
    /// Cell (column, row) marked `G`.
    pub goal: Option<(usize, usize)>,
}

/// A problem in a drawing: its row within the drawing (0-based), column, and what is wrong.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct GridProblem {
    /// Row of the drawing, 0-based.
    pub row: usize,
    /// Character column, 0-based.
    pub column: usize,
    /// What was expected and found.
    pub message: String,
}

/// What a drawing's misplaced character is told: where corners and side walls go.
const CELL_WIDTH: &str = " (each cell is three characters wide: corners '+' and side walls '|' at \
every third column, from the first)";

/// What a drawing `width` characters wide (not 3 * columns + 1) is told: how a row's width
/// follows from its cells, and the widths nearest to the one found, with their columns.
fn width_problem(width: usize) -> String {
    let below = (width.saturating_sub(1) / 3).max(1);
    let nearest = if width <= 4 {
        "4 (1 column)".to_string()
    } else {
        format!(
            "{} ({below} column{}) or {} ({} columns)",
            3 * below + 1,
            if below == 1 { "" } else { "s" },
            3 * below + 4,
            below + 1
        )
    };
    format!(
        "expected rows 3 * columns + 1 characters wide (each cell takes 3 characters, '+--' or \
         '+  ' in a wall row, then the row's last '+': \"+--+--+\" is 2 columns, 7 characters), \
         found {width}; the nearest widths: {nearest}"
    )
}

/// Refuses cell walls that do not fit their cells: a wall must be thinner than the cell it
/// bounds, or neighbouring walls overlap and no corridor is left between them. The one check of
/// a cell maze's sizes, for a generated maze and a drawn one (`[grid]`) alike.
/// A cell is at most `MAX_CELL_SIZE` a side (far inside the coordinates every wall and pose is
/// bounded by): a larger one is a size in centimetres or millimetres taken for metres.
/// The error names the size it is about (`"cell_size"` or `"wall_thickness"`).
pub fn check_cell_walls(cell_size: f64, wall_thickness: f64) -> Result<(), (&'static str, String)> {
    let sizes_ok = cell_size.is_finite() && wall_thickness.is_finite() && cell_size > 0.0;
    if sizes_ok && wall_thickness > 0.0 && wall_thickness < cell_size {
        let most = crate::limits::MAX_CELL_SIZE;
        if cell_size > most {
            return Err((
                "cell_size",
                format!(
                    "expected a cell size in metres of at most {most:?} m, found {cell_size:?} \
                     m (is it in centimetres or millimetres? 25 cm is 0.25)"
                ),
            ));
        }
        return Ok(());
    }
    Err((
        "wall_thickness",
        format!(
            "expected 0 < wall thickness < cell size (a wall thinner than its cell, so a corridor \
         is left between walls), found wall thickness {wall_thickness:?} m and cell size \
         {cell_size:?} m"
        ),
    ))
}

fn problem(row: usize, column: usize, message: impl Into<String>) -> GridProblem {
    GridProblem {
        row,
        column,
        message: message.into(),
    }
}

impl CellMaze {
    /// Parses a drawing (see `docs/world-format.md`). Blank leading and trailing lines are ignored.
    pub fn parse(map: &str) -> Result<CellMaze, GridProblem> {
        let lines: Vec<&str> = map.split('\n').map(|l| l.trim_end_matches('\r')).collect();
        let first = lines.iter().position(|l| !l.trim().is_empty());
        let last = lines.iter().rposition(|l| !l.trim().is_empty());
        let (first, last) = match (first, last) {
            (Some(f), Some(l)) => (f, l),
            _ => return Err(problem(0, 0, "expected a maze drawing, found an empty map")),
        };
        let body = &lines[first..=last];
        if body.len() < 3 || body.len() % 2 == 0 {
            return Err(problem(
                first,
                0,
                format!(
                    "expected an odd number (at least 3) of rows alternating wall rows and cell rows, found {}",
                    body.len()
                ),
            ));
        }
        let width = body
            .iter()
            .map(|l| l.trim_end().chars().count())
            .max()
            .unwrap_or(0);
        if width < 4 || (width - 1) % 3 != 0 {
            return Err(problem(first, width, width_problem(width)));
        }
        let cols = (width - 1) / 3;
        let rows = body.len() / 2;
        let grid: Vec<Vec<char>> = body
            .iter()
            .map(|l| {
                let mut v: Vec<char> = l.trim_end().chars().collect();
                v.resize(width, ' ');
                v
            })
            .collect();
        let mut maze = CellMaze {
            rows,
            cols,
            horizontal: vec![false; (rows + 1) * cols],
            vertical: vec![false; rows * (cols + 1)],
            start: None,
            goal: None,
        };
        for (i, line) in grid.iter().enumerate() {
            let at = first + i;
            if i % 2 == 0 {
                let k = i / 2;
                for (x, &ch) in line.iter().enumerate() {
                    let ok = if x % 3 == 0 {
                        matches!(ch, '+' | ' ' | '-' | '|')
                    } else {
                        matches!(ch, '-' | ' ')
                    };
                    if !ok {
                        let expected = if x % 3 == 0 {
                            "'+', '-', '|' or a space at a corner of a wall row".to_string()
                        } else {
                            format!("'-' or a space in a wall row between corners{CELL_WIDTH}")
                        };
                        return Err(problem(at, x, format!("expected {expected}, found {ch:?}")));
                    }
                }
                for c in 0..cols {
                    maze.horizontal[k * cols + c] =
                        line[3 * c + 1] == '-' || line[3 * c + 2] == '-';
                }
            } else {
                let r = i / 2;
                for (x, &ch) in line.iter().enumerate() {
                    if x % 3 == 0 {
                        if !matches!(ch, '|' | ' ') {
                            return Err(problem(
                                at,
                                x,
                                format!(
                                    "expected '|' or a space between cells{CELL_WIDTH}, found {ch:?}"
                                ),
                            ));
                        }
                        maze.vertical[r * (cols + 1) + x / 3] = ch == '|';
                    } else {
                        let cell = (x / 3, r);
                        match ch {
                            ' ' => {}
                            'S' if maze.start.is_none() => maze.start = Some(cell),
                            'G' if maze.goal.is_none() => maze.goal = Some(cell),
                            'S' | 'G' => {
                                return Err(problem(
                                    at,
                                    x,
                                    format!("a second {ch:?} marker: only one is allowed"),
                                ))
                            }
                            _ => {
                                // A wall's character inside a cell: the row is shifted.
                                let shifted = if matches!(ch, '|' | '+' | '-') {
                                    CELL_WIDTH
                                } else {
                                    ""
                                };
                                return Err(problem(
                                    at,
                                    x,
                                    format!("expected a space, 'S' (start) or 'G' (goal) inside a cell{shifted}, found {ch:?}"),
                                ));
                            }
                        }
                    }
                }
            }
            // A row cut short (a forgotten east border, or an editor that stripped trailing
            // spaces) would be padded with openings and open the outer wall unseen; spaces
            // written out up to the full width are openings on purpose. A misplaced character of
            // the row is told first (above).
            let written = body[i].chars().count();
            if written < width {
                return Err(problem(
                    at,
                    written,
                    format!(
                        "expected every row {width} characters wide, as the widest (3 * columns \
                         + 1), found {written}: end the row with its east border ('|' in a cell \
                         row, '+' in a wall row); an opening in the east wall is written with \
                         spaces up to the full width, which the editor must keep (many strip \
                         trailing spaces)"
                    ),
                ));
            }
        }
        Ok(maze)
    }

    /// Draws the maze back as text (the inverse of `parse`, markers included).
    pub fn draw(&self) -> String {
        let mut out = String::new();
        for k in 0..=self.rows {
            out.push('+');
            for c in 0..self.cols {
                out.push_str(if self.horizontal[k * self.cols + c] {
                    "--+"
                } else {
                    "  +"
                });
            }
            out.push('\n');
            if k == self.rows {
                break;
            }
            for kx in 0..=self.cols {
                out.push(if self.vertical[k * (self.cols + 1) + kx] {
                    '|'
                } else {
                    ' '
                });
                if kx < self.cols {
                    let marker = if self.start == Some((kx, k)) {
                        "S "
                    } else if self.goal == Some((kx, k)) {
                        "G "
                    } else {
                        "  "
                    };
                    out.push_str(marker);
                }
            }
            out.push('\n');
        }
        out
    }

    /// Whether one can move from cell (c, r) to its neighbour in direction `dir`
    /// (0 = east, 1 = north, 2 = west, 3 = south); false at the border.
    pub fn open(&self, c: usize, r: usize, dir: usize) -> bool {
        match dir {
            0 => c + 1 < self.cols && !self.vertical[r * (self.cols + 1) + c + 1],
            1 => r > 0 && !self.horizontal[r * self.cols + c],
            2 => c > 0 && !self.vertical[r * (self.cols + 1) + c],
            _ => r + 1 < self.rows && !self.horizontal[(r + 1) * self.cols + c],
        }
    }

    /// Centre of cell (c, r) in world coordinates.
    pub fn cell_center(&self, origin: [f64; 2], cell_size: f64, c: usize, r: usize) -> [f64; 2] {
        [
            origin[0] + (c as f64 + 0.5) * cell_size,
            origin[1] + (self.rows as f64 - r as f64 - 0.5) * cell_size,
        ]
    }

    /// Wall boxes of the maze, runs of adjacent walls merged into one box.
    pub fn wall_boxes(&self, origin: [f64; 2], cell_size: f64, thickness: f64) -> Vec<WallBox> {
        let mut out = Vec::new();
        for k in 0..=self.rows {
            let y = origin[1] + (self.rows - k) as f64 * cell_size;
            let mut c = 0;
            while c < self.cols {
                if self.horizontal[k * self.cols + c] {
                    let c0 = c;
                    while c < self.cols && self.horizontal[k * self.cols + c] {
                        c += 1;
                    }
                    let a = [origin[0] + c0 as f64 * cell_size, y];
                    let b = [origin[0] + c as f64 * cell_size, y];
                    out.push(WallBox::from_segment(a, b, thickness, 1.0));
                } else {
                    c += 1;
                }
            }
        }
        for k in 0..=self.cols {
            let x = origin[0] + k as f64 * cell_size;
            let mut r = 0;
            while r < self.rows {
                if self.vertical[r * (self.cols + 1) + k] {
                    let r0 = r;
                    while r < self.rows && self.vertical[r * (self.cols + 1) + k] {
                        r += 1;
                    }
                    let a = [x, origin[1] + (self.rows - r0) as f64 * cell_size];
                    let b = [x, origin[1] + (self.rows - r) as f64 * cell_size];
                    out.push(WallBox::from_segment(b, a, thickness, 1.0));
                } else {
                    r += 1;
                }
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const MAP: &str = "\n+--+--+\n|S    |\n+  +--+\n|   G |\n+--+--+\n";

    #[test]
    fn parses_walls_and_markers() {
        let m = CellMaze::parse(MAP).unwrap();
        assert_eq!((m.rows, m.cols), (2, 2));
        assert_eq!(m.start, Some((0, 0)));
        assert_eq!(m.goal, Some((1, 1)));
        assert!(m.open(0, 0, 0) && m.open(0, 0, 3) && !m.open(1, 0, 3) && !m.open(0, 0, 1));
        assert_eq!(m.draw().trim(), MAP.trim());
    }

    #[test]
    fn merges_wall_runs() {
        let m = CellMaze::parse(MAP).unwrap();
        let boxes = m.wall_boxes([0.0, 0.0], 0.25, 0.01);
        // north edge, middle half-line, south edge, west edge, east edge
        assert_eq!(boxes.len(), 5);
        let north = boxes[0];
        assert!((north.half[0] - 0.255).abs() < 1e-12 && (north.center[1] - 0.5).abs() < 1e-12);
    }

    #[test]
    fn reports_bad_characters_with_position() {
        let err = CellMaze::parse("+--+\n|x |\n+--+").unwrap_err();
        assert_eq!((err.row, err.column), (1, 1));
        let err = CellMaze::parse("+--+\n|  |").unwrap_err();
        assert!(err.message.contains("odd number"));
    }

    #[test]
    fn a_row_cut_short_is_refused_and_written_out_spaces_are_openings() {
        // The east border of the second cell row forgotten (or stripped with its spaces).
        let err = CellMaze::parse("+--+--+\n|S    |\n+  +--+\n|   G\n+--+--+").unwrap_err();
        assert_eq!((err.row, err.column), (3, 5));
        assert!(
            err.message.contains("every row 7 characters wide"),
            "{}",
            err.message
        );
        assert!(err.message.contains("east border"), "{}", err.message);
        // The same row with its spaces kept: an opening in the east wall on purpose.
        let open = CellMaze::parse("+--+--+\n|S    |\n+  +--+\n|   G  \n+--+--+").unwrap();
        assert!(!open.vertical[open.cols + 1 + open.cols]);
        assert!(open.vertical[open.cols]);
    }
}
