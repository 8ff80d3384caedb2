//! Wavefront OBJ reader: `no_std`, no allocation, straight from a byte
//! slice, so `include_bytes!("model.obj")` works on a microcontroller.
//!
//! Three ways in, all over the same line parser:
//!
//! - [`ObjReader`] streams [`Statement`]s, one per non-blank line, with no
//!   storage beyond one face (at most `N` corners).
//! - [`ObjMesh`] fills fixed-capacity arrays in the layout of
//!   [`StaticMesh`] and implements [`Mesh`](crate::front::mesh::Mesh).
//! - [`count`] only counts, to size an [`ObjMesh`] or check a file on the
//!   host.
//!
//! ```
//! use zline::Mesh;
//! use zline::obj::ObjMesh;
//!
//! let bytes = b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\nf -4 -2 -1\n";
//! // Up to 8 vertices, 16 corners, 4 faces, 4 corners per face.
//! let mesh = ObjMesh::<8, 16, 4, 4>::parse(bytes).unwrap();
//! assert_eq!((mesh.vertex_count(), mesh.face_count()), (4, 2));
//! assert_eq!(mesh.face(1), &[0, 2, 3]);
//! ```
//!
//! # Syntax
//!
//! - `v x y z` is a vertex. It may go on with `w`, a vertex colour
//!   `r g b`, or both (at most seven numbers in all): they are checked
//!   and ignored. Every number must be finite: `nan`, `inf` and any other
//!   token are errors.
//! - `vt u [v [w]]` is a texture coordinate (`v` is 0 when missing, `w`
//!   is checked and ignored) and `vn x y z` a normal: finite numbers, as
//!   for `v`.
//! - `f` lists 3 or more corners (at most `N`, and at most
//!   [`crate::limits::MAX_FACE_CORNERS`]), each `v`,
//!   `v/vt`, `v//vn` or `v/vt/vn` ([`ObjCorner`]); `vt` and `vn` are
//!   checked like `v` against the `vt` and `vn` lines.
//!   Positive indices count from 1 and may name any line of their kind in
//!   the file, even a later one; negative ones count back from the last
//!   one defined before the face (`-1` is that one). An index out of range
//!   (including one too large for any integer type) is
//!   [`ObjErrorKind::IndexOutOfRange`], naming the index and how many exist.
//! - Every other statement (`o`, `g`, `s`, `usemtl`,
//!   `mtllib`, `l`, `p`, unknown keywords) is skipped without looking at
//!   its arguments; [`Statement::Other`] names its keyword.
//! - `#` starts a comment up to the end of the line. Comment bytes are
//!   never decoded, so they need not be UTF-8.
//! - Lines end with LF, CRLF or a lone CR (old Mac files); the last one may
//!   have no line end. A UTF-8 byte-order mark at the start is skipped.
//!   Spaces, tabs and form feeds separate tokens (a form feed as a space,
//!   so a keyword glued to one is read, not skipped with its face); blank
//!   lines are skipped.
//! - Line continuation with `\` is not supported: a line that ends with
//!   `\` (before any comment), whatever its statement, is
//!   [`ObjErrorKind::LineContinuation`], never read short with the next
//!   line taken as a statement of its own.
//!
//! The first error ends the input; it carries its 1-based line number.

use core::fmt;

use heapless::Vec;

use crate::front::mesh::{MeshArrays, StaticMesh};
use crate::limits::MAX_FACE_CORNERS;

/// Most vertices a file may define: corners are `u16`.
pub const MAX_VERTICES: usize = 1 << 16;

/// A malformed line, or one that does not fit.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ObjError {
    /// 1-based line number.
    pub line: u32,
    /// What is wrong with the line.
    pub kind: ObjErrorKind,
}

/// Which kind of element a face corner's index names.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Element {
    /// A position (`v`).
    Vertex,
    /// A texture coordinate (`vt`).
    TexCoord,
    /// A normal (`vn`).
    Normal,
}

impl fmt::Display for Element {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Element::Vertex => "vertex",
            Element::TexCoord => "texture coordinate",
            Element::Normal => "normal",
        })
    }
}

/// What is wrong with a line.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ObjErrorKind {
    /// A coordinate or index is not a number, is not ASCII, or (for a
    /// coordinate) is NaN or infinite.
    BadNumber,
    /// A `v` or `vn` line has fewer than three coordinates, or a `vt`
    /// line none.
    MissingCoordinate,
    /// A `v` line has more than seven numbers (`x y z`, then `w`, a colour
    /// `r g b`, or both), a `vt` line more than three or a `vn` line more
    /// than three.
    TooManyNumbers,
    /// The line ends with `\`: line continuation is not supported, so the
    /// line would be read short and the next one as a statement of its
    /// own.
    LineContinuation,
    /// A face corner is not `v`, `v/vt`, `v//vn` or `v/vt/vn`.
    BadCorner,
    /// A corner's index is 0, beyond the file's elements of its kind, or
    /// (negative) before the first one.
    IndexOutOfRange {
        /// What the index names.
        element: Element,
        /// The index as written; one beyond the `i64` range is saturated
        /// to it.
        index: i64,
        /// How many elements of that kind the index may name: all in the
        /// file for a positive index, those defined before the face for a
        /// negative one.
        available: u32,
    },
    /// A face has fewer than three corners.
    TooFewCorners,
    /// A face has more corners than the const parameter `N` allows, or
    /// than [`MAX_FACE_CORNERS`] (which the pipeline draws).
    TooManyCorners,
    /// Fixed-capacity storage is full.
    CapacityExceeded(Capacity),
    /// The file defines more than [`MAX_VERTICES`] vertices.
    TooManyVertices,
}

/// Which fixed-capacity store of an [`ObjMesh`] is full.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Capacity {
    /// Positions (const parameter `V`).
    Vertices,
    /// Corners of all faces (const parameter `C`).
    Corners,
    /// Faces (const parameter `F`).
    Faces,
}

impl fmt::Display for Capacity {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Capacity::Vertices => "vertex",
            Capacity::Corners => "corner",
            Capacity::Faces => "face",
        })
    }
}

impl fmt::Display for ObjErrorKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ObjErrorKind::BadNumber => f.write_str("bad or non-finite number"),
            ObjErrorKind::MissingCoordinate => f.write_str("vertex has fewer than 3 coordinates"),
            ObjErrorKind::TooManyNumbers => {
                f.write_str("vertex has more than 7 numbers (x y z, then w and/or r g b)")
            }
            ObjErrorKind::LineContinuation => {
                f.write_str("line continued with \\ (line continuation is not supported)")
            }
            ObjErrorKind::BadCorner => f.write_str("face corner is not v, v/vt, v//vn or v/vt/vn"),
            ObjErrorKind::IndexOutOfRange {
                element,
                index,
                available,
            } => {
                if index.unsigned_abs() >= i64::MAX.unsigned_abs() {
                    write!(f, "{element} index too large")?;
                } else {
                    write!(f, "{element} index {index} out of range")?;
                }
                let noun = match (element, *available == 1) {
                    (Element::Vertex, false) => "vertices",
                    (Element::TexCoord, false) => "texture coordinates",
                    (Element::Normal, false) => "normals",
                    (element, true) => match element {
                        Element::Vertex => "vertex",
                        Element::TexCoord => "texture coordinate",
                        Element::Normal => "normal",
                    },
                };
                if *index < 0 {
                    write!(f, " ({available} {noun} defined before this line)")
                } else {
                    write!(f, " ({available} {noun} in the file)")
                }
            }
            ObjErrorKind::TooFewCorners => f.write_str("face has fewer than 3 corners"),
            ObjErrorKind::TooManyCorners => f.write_str("face has too many corners"),
            ObjErrorKind::CapacityExceeded(c) => write!(f, "{c} capacity exceeded"),
            ObjErrorKind::TooManyVertices => f.write_str("more than 65536 vertices"),
        }
    }
}

impl fmt::Display for ObjError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "OBJ line {}: {}", self.line, self.kind)
    }
}

impl core::error::Error for ObjError {}

/// Lines of the input with their 1-based numbers, comments cut off.
#[derive(Debug, Clone)]
struct Lines<'a> {
    rest: &'a [u8],
    done: bool,
    number: u32,
}

/// The UTF-8 byte-order mark.
const BOM: &[u8] = b"\xEF\xBB\xBF";

impl<'a> Lines<'a> {
    fn new(bytes: &'a [u8]) -> Self {
        let bytes = bytes.strip_prefix(BOM).unwrap_or(bytes);
        Self {
            rest: bytes,
            done: bytes.is_empty(),
            number: 0,
        }
    }
}

impl<'a> Iterator for Lines<'a> {
    type Item = (u32, &'a [u8]);

    fn next(&mut self) -> Option<Self::Item> {
        if self.done {
            return None;
        }
        // LF, CRLF or a lone CR ends a line.
        let (line, rest) = match self.rest.iter().position(|&b| b == b'\n' || b == b'\r') {
            Some(end) => {
                let skip = if self.rest[end..].starts_with(b"\r\n") {
                    2
                } else {
                    1
                };
                (&self.rest[..end], &self.rest[end + skip..])
            }
            None => (self.rest, &[][..]),
        };
        if rest.is_empty() {
            self.done = true;
        }
        self.rest = rest;
        self.number = self.number.saturating_add(1);
        Some((self.number, strip_comment(line)))
    }
}

/// The part of `line` before any `#`.
fn strip_comment(line: &[u8]) -> &[u8] {
    line.split(|&b| b == b'#').next().unwrap_or(&[])
}

/// Whether a line (its comment cut off) ends with `\`, the line
/// continuation this reader refuses.
fn continues(line: &[u8]) -> bool {
    line.iter().rev().find(|b| !b.is_ascii_whitespace()) == Some(&b'\\')
}

/// Most numbers on a `v` line: `x y z`, then `w` and a colour `r g b`.
const MAX_VERTEX_NUMBERS: usize = 7;

/// Whitespace-separated tokens: spaces, tabs and form feeds (the ASCII
/// whitespace bytes, the vertical tab excepted; line ends were cut
/// already). A form feed separates like a space so that a keyword glued
/// to one is still read, never skipped with its statement.
fn tokens(line: &[u8]) -> impl Iterator<Item = &[u8]> {
    line.split(u8::is_ascii_whitespace)
        .filter(|token| !token.is_empty())
}

/// A finite `f32`.
fn parse_coordinate(token: &[u8]) -> Result<f32, ObjErrorKind> {
    let value: f32 = ascii(token)?.parse().map_err(|_| ObjErrorKind::BadNumber)?;
    if value.is_finite() {
        Ok(value)
    } else {
        Err(ObjErrorKind::BadNumber)
    }
}

/// `M` coordinates of a `vt` or `vn` line: at least `required` finite
/// numbers, at most `most` (those beyond `M` are checked and ignored),
/// missing ones 0.
fn numbers<'t, const M: usize>(
    args: &mut impl Iterator<Item = &'t [u8]>,
    required: usize,
    most: usize,
) -> Result<[f32; M], ObjErrorKind> {
    let mut values = [0.0; M];
    let mut count = 0;
    for token in args {
        if count >= most {
            return Err(ObjErrorKind::TooManyNumbers);
        }
        let value = parse_coordinate(token)?;
        if let Some(slot) = values.get_mut(count) {
            *slot = value;
        }
        count += 1;
    }
    if count < required {
        return Err(ObjErrorKind::MissingCoordinate);
    }
    Ok(values)
}

/// A decimal integer with optional sign, saturated to the `i64` range
/// (an index that large is out of range anyway, and reported so): every
/// value of `i64`, `i64::MIN` included, comes back as written.
fn parse_integer(token: &[u8]) -> Result<i64, ObjErrorKind> {
    let (negative, digits) = match token {
        [b'-', rest @ ..] => (true, rest),
        [b'+', rest @ ..] => (false, rest),
        _ => (false, token),
    };
    if digits.is_empty() || !digits.iter().all(u8::is_ascii_digit) {
        return Err(ObjErrorKind::BadNumber);
    }
    // Accumulated with its sign, so that i64::MIN (one more in magnitude
    // than i64::MAX) is reached exactly.
    let sign = if negative { -1 } else { 1 };
    Ok(digits.iter().fold(0i64, |n, &d| {
        n.saturating_mul(10)
            .saturating_add(sign * i64::from(d - b'0'))
    }))
}

fn ascii(token: &[u8]) -> Result<&str, ObjErrorKind> {
    if !token.is_ascii() {
        return Err(ObjErrorKind::BadNumber);
    }
    core::str::from_utf8(token).map_err(|_| ObjErrorKind::BadNumber)
}

/// The (unresolved, 1-based or negative) indices of a face corner: the
/// vertex, and the texture coordinate and normal when present.
fn corner_indices(token: &[u8]) -> Result<[Option<i64>; 3], ObjErrorKind> {
    let mut parts = token.split(|&b| b == b'/');
    let vertex = parts.next().unwrap_or(&[]);
    if vertex.is_empty() {
        return Err(ObjErrorKind::BadCorner);
    }
    let mut indices = [Some(parse_integer(vertex)?), None, None];
    for (k, part) in parts.enumerate() {
        if k >= 2 {
            return Err(ObjErrorKind::BadCorner);
        }
        if !part.is_empty() {
            indices[k + 1] = Some(parse_integer(part)?);
        }
    }
    Ok(indices)
}

/// 0-based index of an OBJ index naming an `element`, given how many were
/// defined so far (`seen`) and in the whole file (`total`).
fn resolve(element: Element, index: i64, seen: usize, total: usize) -> Result<usize, ObjErrorKind> {
    let resolved = if index > 0 {
        usize::try_from(index - 1).ok().filter(|&i| i < total)
    } else {
        usize::try_from(index.unsigned_abs())
            .ok()
            .filter(|&back| back > 0)
            .and_then(|back| seen.checked_sub(back))
    };
    resolved.ok_or(ObjErrorKind::IndexOutOfRange {
        element,
        index,
        available: u32::try_from(if index >= 0 { total } else { seen }).unwrap_or(u32::MAX),
    })
}

/// How many of each element a file defines: so far, or in all.
#[derive(Debug, Clone, Copy, Default)]
struct ElementCounts {
    vertices: usize,
    texcoords: usize,
    normals: usize,
}

impl ElementCounts {
    fn add(&mut self, keyword: &[u8]) {
        match keyword {
            b"v" => self.vertices += 1,
            b"vt" => self.texcoords += 1,
            b"vn" => self.normals += 1,
            _ => {}
        }
    }

    fn get(&self, element: Element) -> usize {
        match element {
            Element::Vertex => self.vertices,
            Element::TexCoord => self.texcoords,
            Element::Normal => self.normals,
        }
    }
}

/// One parsed line, before the face corners are stored anywhere.
enum Parsed<'a> {
    Vertex([f32; 3]),
    TexCoord([f32; 2]),
    Normal([f32; 3]),
    Face,
    Other(&'a [u8]),
}

/// The line parser shared by [`ObjReader`] and [`count`]: face corners go
/// to a callback, so each caller decides where they are stored.
#[derive(Debug, Clone)]
struct Parser<'a> {
    lines: Lines<'a>,
    /// `v`, `vt` and `vn` lines in the whole file.
    total: ElementCounts,
    /// `v`, `vt` and `vn` lines before the current one.
    seen: ElementCounts,
    line: u32,
    failed: bool,
}

impl<'a> Parser<'a> {
    fn new(bytes: &'a [u8]) -> Self {
        let mut total = ElementCounts::default();
        for (_, line) in Lines::new(bytes) {
            if let Some(keyword) = tokens(line).next() {
                total.add(keyword);
            }
        }
        Self {
            lines: Lines::new(bytes),
            total,
            seen: ElementCounts::default(),
            line: 0,
            failed: false,
        }
    }

    fn next_with(
        &mut self,
        corner: &mut impl FnMut(ObjCorner) -> Result<(), ObjErrorKind>,
    ) -> Option<Result<Parsed<'a>, ObjError>> {
        if self.failed {
            return None;
        }
        let (line, text, keyword, mut args) = self.lines.by_ref().find_map(|(number, text)| {
            let mut words = tokens(text);
            words.next().map(|keyword| (number, text, keyword, words))
        })?;
        self.line = line;
        if continues(text) {
            self.failed = true;
            return Some(Err(ObjError {
                line,
                kind: ObjErrorKind::LineContinuation,
            }));
        }
        if keyword != b"v" {
            self.seen.add(keyword);
        }
        let parsed = match keyword {
            b"v" => self.vertex(&mut args).map(Parsed::Vertex),
            b"vt" => numbers::<2>(&mut args, 1, 3).map(Parsed::TexCoord),
            b"vn" => numbers::<3>(&mut args, 3, 3).map(Parsed::Normal),
            b"f" => self.face(&mut args, corner).map(|()| Parsed::Face),
            other => Ok(Parsed::Other(other)),
        };
        Some(parsed.map_err(|kind| {
            self.failed = true;
            ObjError { line, kind }
        }))
    }

    fn vertex<'t>(
        &mut self,
        args: &mut impl Iterator<Item = &'t [u8]>,
    ) -> Result<[f32; 3], ObjErrorKind> {
        if self.seen.vertices >= MAX_VERTICES {
            return Err(ObjErrorKind::TooManyVertices);
        }
        let mut position = [0.0; 3];
        for coordinate in &mut position {
            let token = args.next().ok_or(ObjErrorKind::MissingCoordinate)?;
            *coordinate = parse_coordinate(token)?;
        }
        // w, a colour r g b, or both: numbers, checked and ignored.
        for (k, token) in args.enumerate() {
            if k >= MAX_VERTEX_NUMBERS - 3 {
                return Err(ObjErrorKind::TooManyNumbers);
            }
            parse_coordinate(token)?;
        }
        self.seen.vertices += 1;
        Ok(position)
    }

    fn face<'t>(
        &self,
        args: &mut impl Iterator<Item = &'t [u8]>,
        corner: &mut impl FnMut(ObjCorner) -> Result<(), ObjErrorKind>,
    ) -> Result<(), ObjErrorKind> {
        let mut corners = 0usize;
        for token in args {
            let [vertex, texcoord, normal] = corner_indices(token)?;
            let attribute = |element, index: Option<i64>| {
                index
                    .map(|index| {
                        let seen = self.seen.get(element);
                        let resolved = resolve(element, index, seen, self.total.get(element))?;
                        // Below the file's line count, so below 2^32.
                        Ok(resolved as u32)
                    })
                    .transpose()
            };
            let texcoord = attribute(Element::TexCoord, texcoord)?;
            let normal = attribute(Element::Normal, normal)?;
            let vertex = vertex.ok_or(ObjErrorKind::BadCorner)?;
            let index = resolve(
                Element::Vertex,
                vertex,
                self.seen.vertices,
                self.total.vertices,
            )?;
            let index = u16::try_from(index).map_err(|_| ObjErrorKind::TooManyVertices)?;
            if corners >= MAX_FACE_CORNERS {
                return Err(ObjErrorKind::TooManyCorners);
            }
            corner(ObjCorner {
                vertex: index,
                texcoord,
                normal,
            })?;
            corners += 1;
        }
        if corners < 3 {
            return Err(ObjErrorKind::TooFewCorners);
        }
        Ok(())
    }
}

/// One statement of an OBJ file.
#[derive(Debug, Clone, PartialEq)]
pub enum Statement<'a, const N: usize> {
    /// A `v` line: the position.
    Vertex([f32; 3]),
    /// A `vt` line: `u` and `v`.
    TexCoord([f32; 2]),
    /// A `vn` line: the normal, as written (not normalised).
    Normal([f32; 3]),
    /// An `f` line: its corners.
    Face(Vec<ObjCorner, N>),
    /// Any other statement, skipped: its keyword (for example `b"o"` or
    /// `b"usemtl"`), as raw bytes.
    Other(&'a [u8]),
}

/// A face corner of an OBJ file: 0-based indices of its position, and of
/// its texture coordinate and normal when it names them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ObjCorner {
    /// The `v` line (0 is the first).
    pub vertex: u16,
    /// The `vt` line, if any.
    pub texcoord: Option<u32>,
    /// The `vn` line, if any.
    pub normal: Option<u32>,
}

/// Streams the statements of an OBJ file, one per non-blank line; faces
/// hold at most `N` corners.
///
/// [`ObjReader::new`] makes one cheap pass over the input to count the
/// `v` lines, so that positive indices can be checked against the whole
/// file. After an error the iterator ends.
///
/// ```
/// use zline::obj::{ObjReader, Statement};
///
/// let bytes = b"v 0 0 0\nvt 0.5 1\nv 1 0 0\nv 0 1 0\nf 1/1 2/1 3/1\n";
/// let mut reader = ObjReader::<4>::new(bytes);
/// let mut texcoords = 0;
/// while let Some(statement) = reader.next() {
///     match statement.unwrap() {
///         Statement::Vertex(p) => assert!(p[2] == 0.0),
///         Statement::TexCoord(uv) => {
///             assert_eq!(uv, [0.5, 1.0]);
///             texcoords += 1;
///         }
///         Statement::Face(corners) => {
///             let vertices: Vec<u16> = corners.iter().map(|c| c.vertex).collect();
///             assert_eq!((reader.line(), &vertices[..]), (5, &[0, 1, 2][..]));
///             assert!(corners.iter().all(|c| c.texcoord == Some(0) && c.normal.is_none()));
///         }
///         Statement::Normal(_) | Statement::Other(_) => {}
///     }
/// }
/// assert_eq!(texcoords, 1);
/// ```
#[derive(Debug, Clone)]
pub struct ObjReader<'a, const N: usize> {
    parser: Parser<'a>,
}

impl<'a, const N: usize> ObjReader<'a, N> {
    /// A reader over a whole OBJ file.
    pub fn new(bytes: &'a [u8]) -> Self {
        Self {
            parser: Parser::new(bytes),
        }
    }

    /// 1-based line number of the statement (or error) last returned; 0
    /// before the first.
    pub fn line(&self) -> u32 {
        self.parser.line
    }

    /// Number of `v` lines in the whole file.
    pub fn vertex_total(&self) -> usize {
        self.parser.total.vertices
    }
}

impl<'a, const N: usize> ObjReader<'a, N> {
    /// The next statement, as [`Iterator::next`] gives it, but with a
    /// face's corners handed to `corner` as they are read (at most `N`, as
    /// there) and the face itself empty: for a loader that stores them
    /// anyway, which then never moves a statement holding `N` corners.
    #[cfg_attr(not(feature = "std"), allow(dead_code))]
    pub(crate) fn next_streamed(
        &mut self,
        corner: &mut impl FnMut(ObjCorner),
    ) -> Option<Result<Statement<'a, 0>, ObjError>> {
        let mut count = 0usize;
        let parsed = self.parser.next_with(&mut |index| {
            if count == N {
                return Err(ObjErrorKind::TooManyCorners);
            }
            count += 1;
            corner(index);
            Ok(())
        })?;
        Some(parsed.map(|parsed| statement(parsed, Vec::new())))
    }
}

/// The statement of a parsed line, a face's corners in `face`.
fn statement<const N: usize>(parsed: Parsed<'_>, face: Vec<ObjCorner, N>) -> Statement<'_, N> {
    match parsed {
        Parsed::Vertex(position) => Statement::Vertex(position),
        Parsed::TexCoord(uv) => Statement::TexCoord(uv),
        Parsed::Normal(n) => Statement::Normal(n),
        Parsed::Face => Statement::Face(face),
        Parsed::Other(keyword) => Statement::Other(keyword),
    }
}

impl<'a, const N: usize> Iterator for ObjReader<'a, N> {
    type Item = Result<Statement<'a, N>, ObjError>;

    fn next(&mut self) -> Option<Self::Item> {
        let mut face = Vec::<ObjCorner, N>::new();
        let parsed = self
            .parser
            .next_with(&mut |index| face.push(index).map_err(|_| ObjErrorKind::TooManyCorners))?;
        Some(parsed.map(|parsed| statement(parsed, face)))
    }
}

impl<const N: usize> core::iter::FusedIterator for ObjReader<'_, N> {}

/// Line counts of an OBJ file, from [`count`]: exactly what an
/// [`ObjMesh`] needs (`V >= vertices`, `C >= corners`, `F >= faces`,
/// `N >= max_corners`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct ObjCounts {
    /// `v` lines.
    pub vertices: usize,
    /// `vt` lines.
    pub texcoords: usize,
    /// `vn` lines.
    pub normals: usize,
    /// `f` lines.
    pub faces: usize,
    /// Corners of all faces.
    pub corners: usize,
    /// Triangles after fan-splitting every face: corners − 2 per face.
    pub triangles: usize,
    /// Most corners of any face (0 without faces).
    pub max_corners: usize,
}

impl ObjCounts {
    fn add_face(&mut self, corners: usize) {
        self.faces += 1;
        self.corners = self.corners.saturating_add(corners);
        self.triangles = self.triangles.saturating_add(corners.saturating_sub(2));
        self.max_corners = self.max_corners.max(corners);
    }

    fn add(&mut self, parsed: &Parsed<'_>, corners: usize) {
        match parsed {
            Parsed::Vertex(_) => self.vertices += 1,
            Parsed::Face => self.add_face(corners),
            Parsed::TexCoord(_) => self.texcoords += 1,
            Parsed::Normal(_) => self.normals += 1,
            Parsed::Other(_) => {}
        }
    }
}

/// Checks a whole OBJ file like [`ObjMesh::parse`] and counts its
/// statements, without storing anything (faces may have up to
/// [`MAX_FACE_CORNERS`] corners).
///
/// ```
/// let counts = zline::obj::count(b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n").unwrap();
/// assert_eq!((counts.vertices, counts.faces, counts.triangles), (4, 1, 2));
/// ```
pub fn count(bytes: &[u8]) -> Result<ObjCounts, ObjError> {
    let mut parser = Parser::new(bytes);
    let mut counts = ObjCounts::default();
    loop {
        let mut corners = 0usize;
        let Some(parsed) = parser.next_with(&mut |_| {
            corners += 1;
            Ok(())
        }) else {
            return Ok(counts);
        };
        counts.add(&parsed?, corners);
    }
}

/// An OBJ mesh in fixed-capacity storage: up to `V` vertices, `C` corners
/// in all, `F` faces and `N` corners per face. Same layout as
/// [`StaticMesh`].
///
/// It is large (`12 V + 2 C + 4 F` bytes and a little more), so on a
/// microcontroller keep it in a `static` cell rather than on the stack and
/// fill it with [`ObjMesh::load`]. Its contents are always a valid mesh:
/// a failed load leaves it empty.
#[derive(Debug, Clone)]
pub struct ObjMesh<const V: usize, const C: usize, const F: usize, const N: usize> {
    positions: Vec<[f32; 3], V>,
    corners: Vec<u16, C>,
    face_starts: Vec<u32, F>,
    texcoords: usize,
    normals: usize,
}

impl<const V: usize, const C: usize, const F: usize, const N: usize> Default
    for ObjMesh<V, C, F, N>
{
    fn default() -> Self {
        Self::new()
    }
}

/// The empty mesh, for the impossible case that [`ObjMesh`] holds an
/// invalid one.
const EMPTY: StaticMesh<'static> = match StaticMesh::new(&[], &[], &[]) {
    Ok(mesh) => mesh,
    Err(_) => panic!("the empty mesh is valid"),
};

impl<const V: usize, const C: usize, const F: usize, const N: usize> ObjMesh<V, C, F, N> {
    /// An empty mesh.
    pub const fn new() -> Self {
        Self {
            positions: Vec::new(),
            corners: Vec::new(),
            face_starts: Vec::new(),
            texcoords: 0,
            normals: 0,
        }
    }

    /// Parses a whole OBJ file. Too much data for the capacities is
    /// [`ObjErrorKind::CapacityExceeded`] at the first line that does not
    /// fit.
    pub fn parse(bytes: &[u8]) -> Result<Self, ObjError> {
        let mut mesh = Self::new();
        mesh.load(bytes)?;
        Ok(mesh)
    }

    /// Replaces the contents with a whole OBJ file, in place (see
    /// [`ObjMesh::parse`]). On error the mesh is left empty.
    pub fn load(&mut self, bytes: &[u8]) -> Result<(), ObjError> {
        self.clear();
        let result = self.fill(bytes);
        if result.is_err() {
            self.clear();
        }
        result
    }

    fn clear(&mut self) {
        self.positions.clear();
        self.corners.clear();
        self.face_starts.clear();
        self.texcoords = 0;
        self.normals = 0;
    }

    fn fill(&mut self, bytes: &[u8]) -> Result<(), ObjError> {
        let mut reader = ObjReader::<N>::new(bytes);
        while let Some(statement) = reader.next() {
            self.add(statement?).map_err(|capacity| ObjError {
                line: reader.line(),
                kind: ObjErrorKind::CapacityExceeded(capacity),
            })?;
        }
        Ok(())
    }

    fn add(&mut self, statement: Statement<'_, N>) -> Result<(), Capacity> {
        match statement {
            Statement::Vertex(position) => self
                .positions
                .push(position)
                .map_err(|_| Capacity::Vertices),
            Statement::Face(corners) => {
                let start = u32::try_from(self.corners.len()).map_err(|_| Capacity::Corners)?;
                self.face_starts.push(start).map_err(|_| Capacity::Faces)?;
                corners
                    .iter()
                    .try_for_each(|c| self.corners.push(c.vertex).map_err(|_| Capacity::Corners))
            }
            Statement::TexCoord(_) => {
                self.texcoords += 1;
                Ok(())
            }
            Statement::Normal(_) => {
                self.normals += 1;
                Ok(())
            }
            Statement::Other(_) => Ok(()),
        }
    }

    /// All positions.
    pub fn positions(&self) -> &[[f32; 3]] {
        &self.positions
    }

    /// All corners (0-based vertex indices), face after face.
    pub fn corners(&self) -> &[u16] {
        &self.corners
    }

    /// Where each face starts in [`ObjMesh::corners`].
    pub fn face_starts(&self) -> &[u32] {
        &self.face_starts
    }

    /// Number of `vt` lines read (their values are not kept).
    pub fn texcoord_count(&self) -> usize {
        self.texcoords
    }

    /// Number of `vn` lines read (their values are not kept).
    pub fn normal_count(&self) -> usize {
        self.normals
    }

    /// The same mesh as a [`StaticMesh`] borrowing this one's arrays.
    ///
    /// The contents were checked while parsing, so the check in
    /// [`StaticMesh::new`] cannot fail; if it ever did, this returns an
    /// empty mesh rather than panicking.
    pub fn as_static(&self) -> StaticMesh<'_> {
        StaticMesh::new(&self.positions, &self.corners, &self.face_starts).unwrap_or(EMPTY)
    }
}

impl<const V: usize, const C: usize, const F: usize, const N: usize> MeshArrays
    for ObjMesh<V, C, F, N>
{
    fn positions(&self) -> &[[f32; 3]] {
        &self.positions
    }

    fn corners(&self) -> &[u16] {
        &self.corners
    }

    fn face_starts(&self) -> &[u32] {
        &self.face_starts
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Streamed statements are the iterator's, a face's corners handed
    /// over one by one, at most `N` of them.
    #[test]
    fn streamed_statements_are_the_iterators() {
        let file =
            b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 1\no x\nf 1 2/1 3\nf 1 2 4 3\nf 1 2 3 4 1\n";
        let mut reader = ObjReader::<4>::new(file);
        let mut streamed = ObjReader::<4>::new(file);
        loop {
            let mut corners: Vec<ObjCorner, 4> = Vec::new();
            let got = streamed.next_streamed(&mut |c| corners.push(c).unwrap());
            let want = reader.next();
            assert_eq!(streamed.line(), reader.line());
            match (got, want) {
                (None, None) => break,
                (Some(Ok(Statement::Face(empty))), Some(Ok(Statement::Face(face)))) => {
                    assert!(empty.is_empty());
                    assert_eq!(corners, face);
                }
                (Some(Ok(got)), Some(Ok(want))) => {
                    assert_eq!(std::format!("{got:?}"), std::format!("{want:?}"));
                    assert!(corners.is_empty());
                }
                (Some(Err(got)), Some(Err(want))) => {
                    assert_eq!(got, want);
                    assert_eq!(got.kind, ObjErrorKind::TooManyCorners);
                    assert_eq!(got.line, 9);
                }
                (got, want) => panic!("{got:?} against {want:?}"),
            }
        }
    }

    #[test]
    fn lines_number_and_strip() {
        let mut lines = Lines::new(b"a # x\r\n\nb\xff#\xc4\xe3\nc");
        assert_eq!(lines.next(), Some((1, &b"a "[..])));
        assert_eq!(lines.next(), Some((2, &b""[..])));
        assert_eq!(lines.next(), Some((3, &b"b\xff"[..])));
        assert_eq!(lines.next(), Some((4, &b"c"[..])));
        assert_eq!(lines.next(), None);
        assert_eq!(Lines::new(b"").count(), 0);
        assert_eq!(Lines::new(b"x\n").count(), 1);
        assert_eq!(Lines::new(b"\n").count(), 1);
        // A lone CR ends a line too; CRLF is one line end.
        let lines: [(u32, &[u8]); 4] = [(1, b"a"), (2, b"b"), (3, b""), (4, b"c")];
        assert!(Lines::new(b"a\rb\r\n\rc\r").eq(lines));
        // A byte-order mark is not part of line 1.
        assert_eq!(
            Lines::new(b"\xEF\xBB\xBFv 1").next(),
            Some((1, &b"v 1"[..]))
        );
    }

    #[test]
    fn tokens_split_on_spaces_tabs_cr() {
        let t: [&[u8]; 3] = [b"f", b"1", b"2/3"];
        assert!(tokens(b" \tf  1\t2/3\r").eq(t));
        assert_eq!(tokens(b" \t\r").count(), 0);
    }

    #[test]
    fn numbers() {
        assert_eq!(parse_coordinate(b"-1.5e2"), Ok(-150.0));
        assert_eq!(parse_coordinate(b".5"), Ok(0.5));
        for bad in [
            &b"nan"[..],
            b"inf",
            b"-inf",
            b"1e39",
            b"",
            b"1.0.0",
            b"\xff",
            b"\xef\xbc\x91",
        ] {
            assert_eq!(parse_coordinate(bad), Err(ObjErrorKind::BadNumber));
        }
        assert_eq!(parse_integer(b"-12"), Ok(-12));
        assert_eq!(parse_integer(b"1.0"), Err(ObjErrorKind::BadNumber));
    }

    #[test]
    fn corners() {
        assert_eq!(corner_indices(b"7"), Ok([Some(7), None, None]));
        assert_eq!(corner_indices(b"7/2"), Ok([Some(7), Some(2), None]));
        assert_eq!(corner_indices(b"-7//2"), Ok([Some(-7), None, Some(2)]));
        assert_eq!(corner_indices(b"7/2/3"), Ok([Some(7), Some(2), Some(3)]));
        assert_eq!(corner_indices(b"7/2/3/4"), Err(ObjErrorKind::BadCorner));
        assert_eq!(corner_indices(b"/2"), Err(ObjErrorKind::BadCorner));
        assert_eq!(corner_indices(b"7/x"), Err(ObjErrorKind::BadNumber));
    }

    #[test]
    fn integers_saturate() {
        assert_eq!(parse_integer(b"+12"), Ok(12));
        assert_eq!(parse_integer(b"18446744073709551616"), Ok(i64::MAX));
        assert_eq!(parse_integer(b"-99999999999999999999999"), Ok(i64::MIN));
        assert_eq!(parse_integer(b"-9223372036854775808"), Ok(i64::MIN));
        assert_eq!(parse_integer(b"9223372036854775807"), Ok(i64::MAX));
        for bad in [&b""[..], b"-", b"+", b"1-", b"--1", b"1e3", b" 1"] {
            assert_eq!(parse_integer(bad), Err(ObjErrorKind::BadNumber), "{bad:?}");
        }
    }

    #[test]
    fn resolution() {
        let out = |index: i64, available: u32| {
            Err(ObjErrorKind::IndexOutOfRange {
                element: Element::Vertex,
                index,
                available,
            })
        };
        let r = |index, seen, total| resolve(Element::Vertex, index, seen, total);
        assert_eq!(r(1, 0, 3), Ok(0));
        assert_eq!(r(3, 0, 3), Ok(2));
        assert_eq!(r(4, 0, 3), out(4, 3));
        assert_eq!(r(0, 2, 3), out(0, 3));
        assert_eq!(r(-1, 2, 3), Ok(1));
        assert_eq!(r(-2, 2, 3), Ok(0));
        assert_eq!(r(-3, 2, 3), out(-3, 2));
        assert_eq!(r(i64::MIN, 2, 3), out(i64::MIN, 2));
        assert_eq!(r(i64::MAX, 2, 3), out(i64::MAX, 3));
    }

    #[test]
    fn as_static_matches() {
        let mesh = ObjMesh::<4, 8, 2, 4>::parse(b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3").unwrap();
        let s = mesh.as_static();
        assert_eq!(s.positions(), mesh.positions());
        assert_eq!(s.corners(), &[0, 1, 2]);
        assert_eq!(s.face_starts(), &[0]);
    }
}
