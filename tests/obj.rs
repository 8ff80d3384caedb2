//! The OBJ reader on hand-written inputs: every accepted syntax, every
//! error kind with its line, and random inputs that must never panic.

use proptest::prelude::*;
use zline::obj::{
    Capacity, Element, ObjCorner, ObjCounts, ObjError, ObjErrorKind, ObjMesh, ObjReader, Statement,
    count,
};
use zline::{Mesh, StaticMesh};

/// Roomy enough for every hand-written input; 8 corners per face.
type Small = ObjMesh<16, 64, 16, 8>;

const TRIANGLE: &[u8] = b"v 0 0 0\nv 1 0 0\nv 0 1 0\n";

fn parse(bytes: &[u8]) -> Small {
    match Small::parse(bytes) {
        Ok(mesh) => mesh,
        Err(e) => panic!("{e} in {:?}", String::from_utf8_lossy(bytes)),
    }
}

fn faces(mesh: &impl Mesh) -> Vec<Vec<u16>> {
    (0..mesh.face_count())
        .map(|f| mesh.face(f).to_vec())
        .collect()
}

fn error(bytes: &[u8]) -> ObjError {
    let from_mesh = Small::parse(bytes).expect_err("should fail");
    if !matches!(
        from_mesh.kind,
        ObjErrorKind::CapacityExceeded(_) | ObjErrorKind::TooManyCorners
    ) {
        assert_eq!(count(bytes), Err(from_mesh), "count and parse disagree");
    }
    from_mesh
}

fn at(line: u32, kind: ObjErrorKind) -> ObjError {
    ObjError { line, kind }
}

fn with_triangle(tail: &str) -> Vec<u8> {
    [TRIANGLE, tail.as_bytes()].concat()
}

#[test]
fn each_corner_format() {
    // One texture coordinate and one normal for the corners to name.
    for face in [
        "f 1 2 3\n",
        "f 1/1 2/1 3/1\n",
        "f 1//1 2//1 3//1\n",
        "f 1/1/1 2/1/1 3/1/1\n",
        "f 1/ 2/ 3/\n",
        "f 1/1/ 2// 3/-1/-1\n",
    ] {
        let mesh = parse(&with_triangle(&format!("vt 0 0\nvn 0 0 1\n{face}")));
        assert_eq!(faces(&mesh), [[0, 1, 2]], "{face}");
    }
}

#[test]
fn positions_exact_and_extra_numbers_ignored() {
    let mesh = parse(b"v 1.5 -2e3 .25 1.0\nv\t0.1  0.2\t\t0.3 0.9 0.8 0.7\nv -0 +4 5.\nf 1 2 3");
    assert_eq!(
        mesh.positions(),
        [[1.5, -2000.0, 0.25], [0.1, 0.2, 0.3], [-0.0, 4.0, 5.0]]
    );
}

#[test]
fn negative_indices_count_back_from_the_line() {
    let bytes = b"v 0 0 0\nv 1 0 0\nv 1 1 0\nf -3 -2 -1\nv 0 1 0\nf -4 -2 -1\nf 1 -1 -2";
    let mesh = parse(bytes);
    assert_eq!(faces(&mesh), [vec![0, 1, 2], vec![0, 2, 3], vec![0, 3, 2]]);
}

#[test]
fn positive_indices_may_name_later_vertices() {
    let mesh = parse(b"f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n");
    assert_eq!(faces(&mesh), [[0, 1, 2]]);
}

#[test]
fn cornell_box_like() {
    let bytes = b"# cornell box, after tinyobjloader's copy of embree's\n\
# original cornell box data\n  # comment\n\n# empty line including some space\n   \n\n\
mtllib cornell_box.mtl\n\no floor\nusemtl white\n\
v 552.8 0.0   0.0\nv 0.0   0.0   0.0\nv 0.0   0.0 559.2\nv 549.6 0.0 559.2\n\n\
f 1 2 3 4 \n\no light\nusemtl light\n\
v 343.0 548.0 227.0\nv 343.0 548.0 332.0\nv 213.0 548.0 332.0\nv 213.0 548.0 227.0\n\
f -4 -3 -2 -1\n\no ceiling\nusemtl white\n\
v 556.0 548.8 0.0\nv 556.0 548.8 559.2\nv 0.0 548.8 559.2\nv 0.0 548.8 0.0\n\
f -4 -3 -2 -1\n";
    let mesh = parse(bytes);
    assert_eq!(mesh.vertex_count(), 12);
    assert_eq!(faces(&mesh), [[0, 1, 2, 3], [4, 5, 6, 7], [8, 9, 10, 11]]);
    assert_eq!(mesh.position(4), [343.0, 548.0, 227.0]);
    let counts = count(bytes).unwrap();
    assert_eq!(
        (counts.faces, counts.triangles, counts.max_corners),
        (3, 6, 4)
    );
}

#[test]
fn crlf_and_missing_final_newline() {
    let lf = parse(b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    let crlf = parse(b"v 0 0 0\r\nv 1 0 0\r\n\r\nv 0 1 0\r\nf 1 2 3\r\n");
    let bare = parse(b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3");
    let bare_crlf = parse(b"v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nf 1 2 3\r");
    for mesh in [&crlf, &bare, &bare_crlf] {
        assert_eq!(mesh.positions(), lf.positions());
        assert_eq!(faces(mesh), faces(&lf));
    }
    // A bad last line without a line end still gets its line number.
    assert_eq!(
        error(b"v 0 0 0\r\n\r\nv 1 x 0"),
        at(3, ObjErrorKind::BadNumber)
    );
}

#[test]
fn comments_are_not_decoded() {
    let bytes =
        b"# \xc4\xe3\xba\xc3\nv 0 0 0 # \xff\xfe\nv 1 0 0#\x80\nv 0 1 0\nf 1 2 3 #\xc4\n#\xff";
    let mesh = parse(bytes);
    assert_eq!(mesh.vertex_count(), 3);
    assert_eq!(faces(&mesh), [[0, 1, 2]]);
    // A number cut short by a comment is still a number.
    assert_eq!(
        parse(b"v 0 0 0#1\nv 1 0 0\nv 0 1 0\nf 1 2 3").position(0),
        [0.0; 3]
    );
}

#[test]
fn other_statements_are_skipped_and_named() {
    let bytes = b"mtllib a.mtl\no thing \xff\ng group\ns off\nusemtl m\n\
v 0 0 0\nvt 0 0\nvt 1 0\nvn 0 0 1\nv 1 0 0\nv 0 1 0\n\
l 1 2\np 1\nfoo bar baz\nvp 0.5\ncstype bezier\nf 1/1/1 2/2/1 3/1/1\n";
    let mut keywords = Vec::new();
    let mut reader = ObjReader::<4>::new(bytes);
    assert_eq!(reader.vertex_total(), 3);
    for statement in &mut reader {
        if let Statement::Other(keyword) = statement.unwrap() {
            keywords.push(String::from_utf8(keyword.to_vec()).unwrap());
        }
    }
    assert_eq!(
        keywords,
        [
            "mtllib", "o", "g", "s", "usemtl", "l", "p", "foo", "vp", "cstype"
        ]
    );
    let mesh = parse(bytes);
    assert_eq!((mesh.texcoord_count(), mesh.normal_count()), (2, 1));
    assert_eq!(faces(&mesh), [[0, 1, 2]]);
    assert_eq!(
        count(bytes),
        Ok(ObjCounts {
            vertices: 3,
            texcoords: 2,
            normals: 1,
            faces: 1,
            corners: 3,
            triangles: 1,
            max_corners: 3,
        })
    );
}

#[test]
fn reader_reports_lines_and_statements() {
    let bytes = b"\nv 0 0 0\n# c\nv 1 0 0\nv 0 1 0\n\nf 3 2 1\n";
    let mut reader = ObjReader::<3>::new(bytes);
    let mut seen = Vec::new();
    while let Some(statement) = reader.next() {
        seen.push((reader.line(), statement.unwrap()));
    }
    let corner = |vertex| ObjCorner {
        vertex,
        texcoord: None,
        normal: None,
    };
    let face = heapless::Vec::from_slice(&[corner(2), corner(1), corner(0)]).unwrap();
    assert_eq!(
        seen,
        [
            (2, Statement::Vertex([0.0, 0.0, 0.0])),
            (4, Statement::Vertex([1.0, 0.0, 0.0])),
            (5, Statement::Vertex([0.0, 1.0, 0.0])),
            (7, Statement::Face(face)),
        ]
    );
}

#[test]
fn reader_stops_after_an_error() {
    let mut reader = ObjReader::<4>::new(b"v 0 0 0\nv x 0 0\nv 1 1 1\n");
    assert!(matches!(reader.next(), Some(Ok(Statement::Vertex(_)))));
    assert_eq!(reader.next(), Some(Err(at(2, ObjErrorKind::BadNumber))));
    assert_eq!(reader.line(), 2);
    assert_eq!(reader.next(), None);
    assert_eq!(reader.next(), None);
}

#[test]
fn quads_and_pentagons() {
    let bytes = b"v 0 0 0\nv 1 0 0\nv 2 1 0\nv 1 2 0\nv 0 1 0\nf 1 2 3 4\nf 1 2 3 4 5\nf 5 4 3\n";
    let mesh = parse(bytes);
    assert_eq!(
        faces(&mesh),
        [vec![0, 1, 2, 3], vec![0, 1, 2, 3, 4], vec![4, 3, 2]]
    );
    assert_eq!(mesh.face_starts(), [0, 4, 9]);
    assert_eq!(mesh.corners().len(), 12);
    let counts = count(bytes).unwrap();
    assert_eq!(
        (
            counts.faces,
            counts.corners,
            counts.triangles,
            counts.max_corners
        ),
        (3, 12, 6, 5)
    );
}

#[test]
fn as_static_is_the_same_mesh() {
    let mesh = parse(b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\nf 3 2 1");
    let s: StaticMesh<'_> = mesh.as_static();
    assert_eq!(s.positions(), mesh.positions());
    assert_eq!(s.corners(), mesh.corners());
    assert_eq!(s.face_starts(), mesh.face_starts());
    assert_eq!(faces(&s), faces(&mesh));
}

#[test]
fn empty_inputs() {
    for bytes in [&b""[..], b"\n", b"\r\n", b"# only a comment", b"   \t\n\n"] {
        let mesh = parse(bytes);
        assert_eq!((mesh.vertex_count(), mesh.face_count()), (0, 0));
        assert_eq!(count(bytes), Ok(ObjCounts::default()));
    }
}

#[test]
fn bad_numbers() {
    use ObjErrorKind::BadNumber;
    for (tail, line) in [
        ("v 1 x 3\n", 4),
        ("v 1 2 3\nv nan 0 0\n", 5),
        ("v NaN 0 0\n", 4),
        ("v 0 inf 0\n", 4),
        ("v 0 0 -inf\n", 4),
        ("v 0 0 infinity\n", 4),
        ("v 1e39 0 0\n", 4),
        ("v 1.0.0 0 0\n", 4),
        ("v 0,5 0 0\n", 4),
        ("\n\nv \u{ff11} 0 0\n", 6),
        ("f 1 2 x\n", 4),
        ("f 1 2 3.0\n", 4),
        ("f 1/a 2 3\n", 4),
        ("f 1 2//b 3\n", 4),
        ("f 1 2 3/1/1.5\n", 4),
        // Issue 28, item 4: what follows z must be numbers too.
        ("v 0 1 0 not-a-number\n", 4),
        ("v 0 1 0 1 x\n", 4),
        ("v 0 1 0 nan\n", 4),
        ("v 0 1 0 1 inf 0 0\n", 4),
    ] {
        assert_eq!(error(&with_triangle(tail)), at(line, BadNumber), "{tail:?}");
    }
    assert_eq!(error(b"v 0 \xff 0\n"), at(1, BadNumber));
}

/// Issue 28, item 4: a line continued with `\` is an error whatever its
/// statement, never a line dropped or a continuation read as a statement
/// of its own (a `\` after a vertex's z was dropped, and the continued
/// line skipped as an unknown keyword).
#[test]
fn line_continuations_are_errors() {
    use ObjErrorKind::LineContinuation;
    for (tail, line) in [
        ("v 0 1 0 \\\n1 1 1\n", 4),
        ("v 0 1 \\\n0\n", 4),
        ("f 1 2 3 \\\n", 4),
        ("f 1 2 \\\n3\n", 4),
        ("vt 0 0 \\\n0\n", 4),
        ("usemtl red\\\n", 4),
        ("\n\ng 1 2 \\ # comment\n", 6),
        ("v 0 1 0\\\r\n", 4),
    ] {
        assert_eq!(
            error(&with_triangle(tail)),
            at(line, LineContinuation),
            "{tail:?}"
        );
    }
    // A backslash inside a line is no continuation.
    parse(&with_triangle("g a\\b c\nf 1 2 3\n"));
}

/// Issue 28, item 4: after z come at most four numbers (w, or a colour
/// r g b, or both).
#[test]
fn a_vertex_has_at_most_seven_numbers() {
    let mesh = parse(b"v 1 2 3 1 0.5 0.5 0.5\nv 1 2 3\nv 1 2 3 1\nf 1 2 3\n");
    assert_eq!(mesh.vertex_count(), 3);
    assert_eq!(
        error(&with_triangle("v 1 2 3 1 0.5 0.5 0.5 1\n")),
        at(4, ObjErrorKind::TooManyNumbers)
    );
}

/// A form feed separates tokens like a space (as every ASCII whitespace
/// byte but the vertical tab does): a keyword glued to one is still read,
/// never skipped as an unknown statement with its face.
#[test]
fn form_feeds_separate_tokens() {
    let mesh = parse(b"v\x0c0 0 0\nv 1\x0c0 0\nv 0 1 0\x0c\n\x0cf 1 2\x0c3\n");
    assert_eq!(faces(&mesh), [[0, 1, 2]]);
    assert_eq!(mesh.positions()[1], [1.0, 0.0, 0.0]);
}

#[test]
fn missing_coordinates_and_bad_corners() {
    assert_eq!(error(b"v 1 2\n"), at(1, ObjErrorKind::MissingCoordinate));
    assert_eq!(
        error(b"v 1 2 # 3\n"),
        at(1, ObjErrorKind::MissingCoordinate)
    );
    assert_eq!(error(b"v\n"), at(1, ObjErrorKind::MissingCoordinate));
    for tail in ["f 1 2 /3\n", "f 1 2 3/1/1/1\n", "f 1 2 //\n"] {
        assert_eq!(
            error(&with_triangle(tail)),
            at(4, ObjErrorKind::BadCorner),
            "{tail:?}"
        );
    }
}

fn out_of_range(element: Element, index: i64, available: u32) -> ObjErrorKind {
    ObjErrorKind::IndexOutOfRange {
        element,
        index,
        available,
    }
}

#[test]
fn indices_out_of_range() {
    use Element::Vertex;
    for (tail, index, available) in [
        ("f 0 1 2\n", 0, 3),
        ("f 1 2 4\n", 4, 3),
        ("f 1 2 -4\n", -4, 3),
        ("f 1 2 -0\n", 0, 3),
        ("f 1 2 -99999999999\n", -99_999_999_999, 3),
        // Issue 7, item 9: 2^64 is an index out of range, not a bad number.
        ("f 1 2 18446744073709551616\n", i64::MAX, 3),
        // Issue 28, item 5: the most negative i64 is reported as written
        // (it was -i64::MAX), and one beyond it saturates to it.
        ("f -9223372036854775808 1 2\n", i64::MIN, 3),
        ("f 1 2 -9223372036854775807\n", -i64::MAX, 3),
        ("f 1 2 -9223372036854775809\n", i64::MIN, 3),
        ("f 1 2 -99999999999999999999999\n", i64::MIN, 3),
    ] {
        assert_eq!(
            error(&with_triangle(tail)),
            at(4, out_of_range(Vertex, index, available)),
            "{tail:?}"
        );
    }
    // Positive indices are checked against the whole file ...
    assert_eq!(
        error(b"v 0 0 0\nf 1 2 3\nv 0 0 0\n"),
        at(2, out_of_range(Vertex, 3, 2))
    );
    // ... negative ones against the vertices before the face.
    assert_eq!(
        error(b"v 0 0 0\nv 1 0 0\nf -1 -2 -3\nv 0 1 0\n"),
        at(3, out_of_range(Vertex, -3, 2))
    );
    assert_eq!(
        error(b"# no vertices yet\nf -1 -2 -3\n"),
        at(2, out_of_range(Vertex, -1, 0))
    );
}

#[test]
fn texture_and_normal_indices_are_checked() {
    // Issue 7, item 9: one `vt` line, three corners naming vt 1, 2 and 3.
    assert_eq!(
        error(&with_triangle("vt 0 0\nf 1/1 2/2 3/3\n")),
        at(5, out_of_range(Element::TexCoord, 2, 1))
    );
    assert_eq!(
        error(&with_triangle("f 1//1 2//1 3//1\n")),
        at(4, out_of_range(Element::Normal, 1, 0))
    );
    assert_eq!(
        error(&with_triangle("vn 0 0 1\nf 1//-2 2//-1 3//-1\n")),
        at(5, out_of_range(Element::Normal, -2, 1))
    );
    // Later `vt` lines count for positive indices, as `v` lines do.
    let mesh = parse(&with_triangle("f 1/2 2/2 3/1\nvt 0 0\nvt 1 1\n"));
    assert_eq!(faces(&mesh), [[0, 1, 2]]);
    assert_eq!(
        error(&with_triangle("f 1/x 2 3\n")),
        at(4, ObjErrorKind::BadNumber)
    );
}

#[test]
fn cr_only_line_endings_are_lines() {
    // Issue 7, item 7: read as one line, this hid the NaN and the bad index.
    assert_eq!(
        error(b"v 0 0 0\rv 1 0 nan\rf 1 2 99\r"),
        at(2, ObjErrorKind::BadNumber)
    );
    assert_eq!(
        error(b"v 0 0 0\rv 1 0 0\rv 0 1 0\rf 1 2 99\r"),
        at(4, out_of_range(Element::Vertex, 99, 3))
    );
    let mesh = parse(b"v 0 0 0\rv 1 0 0\r\nv 0 1 0\r\rf 1 2 3");
    assert_eq!(
        (mesh.vertex_count(), faces(&mesh)),
        (3, vec![vec![0, 1, 2]])
    );
    assert_eq!(count(b"v 0 0 0\r\rv 1 0 0\r").map(|c| c.vertices), Ok(2));
}

#[test]
fn a_byte_order_mark_is_skipped() {
    // Issue 7, item 8: the BOM made line 1 an unknown keyword.
    let bom = [&b"\xEF\xBB\xBF"[..], TRIANGLE, b"f 1 2 3\n"].concat();
    let mesh = parse(&bom);
    assert_eq!((mesh.vertex_count(), mesh.face_count()), (3, 1));
    let bad = [&b"\xEF\xBB\xBFv 0 0\n"[..], TRIANGLE].concat();
    assert_eq!(error(&bad), at(1, ObjErrorKind::MissingCoordinate));
    // A BOM anywhere else is not skipped.
    assert_eq!(
        error(&[TRIANGLE, b"\xEF\xBB\xBFv 0 0 0\nf 1 2 4\n"].concat()),
        at(5, out_of_range(Element::Vertex, 4, 3))
    );
}

#[test]
fn corner_counts() {
    assert_eq!(
        error(&with_triangle("f 1 2\n")),
        at(4, ObjErrorKind::TooFewCorners)
    );
    assert_eq!(
        error(&with_triangle("\nf\n")),
        at(5, ObjErrorKind::TooFewCorners)
    );
    assert_eq!(
        error(&with_triangle("f 1 # 2 3\n")),
        at(4, ObjErrorKind::TooFewCorners)
    );
    // N = 8: eight corners fit, nine do not.
    parse(&with_triangle("f 1 2 3 1 2 3 1 2\n"));
    assert_eq!(
        error(&with_triangle("f 1 2 3\nf 1 2 3 1 2 3 1 2 3\n")),
        at(5, ObjErrorKind::TooManyCorners)
    );
    let mut reader = ObjReader::<3>::new(b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3 4\n");
    assert_eq!(
        reader.find(Result::is_err),
        Some(Err(at(5, ObjErrorKind::TooManyCorners)))
    );
    // `count` has no corner limit.
    assert_eq!(
        count(&with_triangle("f 1 2 3 1 2 3 1 2 3\n"))
            .unwrap()
            .max_corners,
        9
    );
}

#[test]
fn capacities() {
    use Capacity::{Corners, Faces, Vertices};
    use ObjErrorKind::CapacityExceeded;
    let bytes = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\n\nf 2 4 3\n";
    assert!(ObjMesh::<4, 6, 2, 3>::parse(bytes).is_ok());
    assert_eq!(
        ObjMesh::<3, 6, 2, 3>::parse(bytes).err(),
        Some(at(4, CapacityExceeded(Vertices)))
    );
    assert_eq!(
        ObjMesh::<4, 5, 2, 3>::parse(bytes).err(),
        Some(at(7, CapacityExceeded(Corners)))
    );
    assert_eq!(
        ObjMesh::<4, 6, 1, 3>::parse(bytes).err(),
        Some(at(7, CapacityExceeded(Faces)))
    );
    assert_eq!(
        ObjMesh::<0, 0, 0, 3>::parse(b"# x\nv 0 0 0").err(),
        Some(at(2, CapacityExceeded(Vertices)))
    );
}

#[test]
fn too_many_vertices() {
    let mut bytes = b"v 0 0 0\n".repeat(65_536);
    assert_eq!(count(&bytes).unwrap().vertices, 65_536);
    bytes.extend_from_slice(b"f 1 65536 -1\n");
    assert_eq!(count(&bytes).unwrap().faces, 1);
    bytes.extend_from_slice(b"v 0 0 0\n");
    assert_eq!(
        count(&bytes),
        Err(at(65_538, ObjErrorKind::TooManyVertices))
    );
    let mut reader = ObjReader::<3>::new(&bytes);
    assert_eq!(reader.vertex_total(), 65_537);
    assert_eq!(
        reader.find(Result::is_err),
        Some(Err(at(65_538, ObjErrorKind::TooManyVertices)))
    );
}

#[test]
fn load_replaces_and_failed_load_empties() {
    let mut mesh = Small::new();
    mesh.load(&with_triangle("f 1 2 3\nvt 0 0\n")).unwrap();
    assert_eq!((mesh.face_count(), mesh.texcoord_count()), (1, 1));
    mesh.load(b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\nvn 0 0 1\n")
        .unwrap();
    assert_eq!(faces(&mesh), [[0, 1, 2, 3]]);
    assert_eq!((mesh.texcoord_count(), mesh.normal_count()), (0, 1));
    assert_eq!(
        mesh.load(&with_triangle("f 1 2 3\nf 1 2 9\n")),
        Err(at(5, out_of_range(Element::Vertex, 9, 3)))
    );
    assert_eq!((mesh.vertex_count(), mesh.face_count()), (0, 0));
    assert!(mesh.corners().is_empty() && mesh.normal_count() == 0);
}

#[test]
fn display_names_the_line() {
    let e = error(&with_triangle("\nf 1 2 0\n"));
    assert_eq!(
        e.to_string(),
        "OBJ line 5: vertex index 0 out of range (3 vertices in the file)"
    );
    let e = error(&with_triangle("f 1 2 -7\n"));
    assert_eq!(
        e.to_string(),
        "OBJ line 4: vertex index -7 out of range (3 vertices defined before this line)"
    );
    let e = error(&with_triangle("f 1 2 99999999999999999999\n"));
    assert_eq!(
        e.to_string(),
        "OBJ line 4: vertex index too large (3 vertices in the file)"
    );
    let e = error(&with_triangle("vt 0 0\nf 1/2 2 3\n"));
    assert_eq!(
        e.to_string(),
        "OBJ line 5: texture coordinate index 2 out of range (1 texture coordinate in the file)"
    );
    let e = at(12, ObjErrorKind::CapacityExceeded(Capacity::Faces));
    assert_eq!(e.to_string(), "OBJ line 12: face capacity exceeded");
    let boxed: Box<dyn std::error::Error> = Box::new(e);
    assert!(boxed.to_string().contains("12"));
}

const VALID: &[u8] = b"# \xc4\xe3\nmtllib m.mtl\no x\nv 0 0 0\nv 1 0 0 1\nv 1 1 0\r\nv 0 1 0\n\
vt 0 0\nvn 0 0 1\nf 1/1/1 2/1/1 3/1/1 4/1/1\ns 1\nf -4//1 -2//1 -1//1\nf 3 2 1";

/// Parses `bytes` every way and checks the ways agree; panics on a bug.
fn check_consistent(bytes: &[u8]) {
    type Mesh8 = ObjMesh<64, 256, 64, 8>;
    let counted = count(bytes);
    let parsed = Mesh8::parse(bytes);
    let streamed = ObjReader::<8>::new(bytes).count();
    assert!(streamed <= bytes.len() + 1);
    match (&parsed, &counted) {
        (Ok(mesh), Ok(c)) => {
            assert_eq!(
                (mesh.vertex_count(), mesh.face_count(), mesh.corners().len()),
                (c.vertices, c.faces, c.corners)
            );
            assert_eq!(
                (mesh.texcoord_count(), mesh.normal_count()),
                (c.texcoords, c.normals)
            );
            assert!(StaticMesh::new(mesh.positions(), mesh.corners(), mesh.face_starts()).is_ok());
            assert!(mesh.positions().iter().flatten().all(|x| x.is_finite()));
        }
        (Ok(_), Err(e)) => panic!("count failed ({e}) where parse succeeded"),
        (Err(e), Ok(c)) => {
            let fits = c.vertices <= 64 && c.corners <= 256 && c.faces <= 64 && c.max_corners <= 8;
            assert!(!fits, "parse failed ({e}) on a mesh that fits: {c:?}");
        }
        (Err(p), Err(c)) => {
            assert!(p.line <= c.line);
            if !matches!(
                p.kind,
                ObjErrorKind::CapacityExceeded(_) | ObjErrorKind::TooManyCorners
            ) {
                assert_eq!(p, c);
            }
        }
    }
}

#[test]
fn valid_sample_parses() {
    let mesh = parse(VALID);
    assert_eq!(
        faces(&mesh),
        [vec![0, 1, 2, 3], vec![0, 2, 3], vec![2, 1, 0]]
    );
    check_consistent(VALID);
}

/// Bytes that reach deep into the parser more often than uniform ones.
fn obj_ish_byte() -> impl Strategy<Value = u8> {
    prop_oneof![
        3 => prop::sample::select(b"vf \n\t\r/#-+.0123456789eE".to_vec()),
        1 => any::<u8>(),
    ]
}

#[derive(Debug, Clone)]
enum Edit {
    Replace(usize, u8),
    Insert(usize, u8),
    Delete(usize),
}

fn edit() -> impl Strategy<Value = Edit> {
    prop_oneof![
        (any::<usize>(), obj_ish_byte()).prop_map(|(i, b)| Edit::Replace(i, b)),
        (any::<usize>(), obj_ish_byte()).prop_map(|(i, b)| Edit::Insert(i, b)),
        any::<usize>().prop_map(Edit::Delete),
    ]
}

fn apply(bytes: &mut Vec<u8>, edit: &Edit) {
    let n = bytes.len();
    match *edit {
        Edit::Replace(i, b) if n > 0 => bytes[i % n] = b,
        Edit::Insert(i, b) => bytes.insert(i % (n + 1), b),
        Edit::Delete(i) if n > 0 => {
            bytes.remove(i % n);
        }
        _ => {}
    }
}

proptest! {
    #[test]
    fn random_bytes_never_panic(bytes in prop::collection::vec(any::<u8>(), 0..200)) {
        check_consistent(&bytes);
    }

    #[test]
    fn obj_ish_bytes_never_panic(bytes in prop::collection::vec(obj_ish_byte(), 0..200)) {
        check_consistent(&bytes);
    }

    #[test]
    fn mutated_obj_never_panics(edits in prop::collection::vec(edit(), 1..8)) {
        let mut bytes = VALID.to_vec();
        for e in &edits {
            apply(&mut bytes, e);
        }
        check_consistent(&bytes);
    }
}

/// `vt` and `vn` lines are read (`vt`'s `v` 0 when missing, its `w`
/// checked and ignored), and a face's corners name them, 0-based, by
/// positive or negative index.
#[test]
fn texture_coordinates_and_normals_are_read() {
    let bytes = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0.25\nvt 0.5 0.75 1\nvn 0 0 2\n\
f 1/1/1 2/2/1 3/-1/-1\nf 1//1 2 3/1\n";
    let mut texcoords = Vec::new();
    let mut normals = Vec::new();
    let mut faces = Vec::new();
    for statement in ObjReader::<4>::new(bytes) {
        match statement.unwrap() {
            Statement::TexCoord(uv) => texcoords.push(uv),
            Statement::Normal(n) => normals.push(n),
            Statement::Face(corners) => faces.push(
                corners
                    .iter()
                    .map(|c| (c.vertex, c.texcoord, c.normal))
                    .collect::<Vec<_>>(),
            ),
            Statement::Vertex(_) | Statement::Other(_) => {}
        }
    }
    assert_eq!(texcoords, [[0.25, 0.0], [0.5, 0.75]]);
    assert_eq!(normals, [[0.0, 0.0, 2.0]]);
    assert_eq!(
        faces,
        [
            vec![
                (0, Some(0), Some(0)),
                (1, Some(1), Some(0)),
                (2, Some(1), Some(0))
            ],
            vec![(0, None, Some(0)), (1, None, None), (2, Some(0), None)],
        ]
    );
}

/// Malformed `vt` and `vn` lines are errors naming their line.
#[test]
fn malformed_texture_coordinates_and_normals_are_errors() {
    let cases: [(&[u8], u32, ObjErrorKind); 6] = [
        (b"v 0 0 0\nvt\n", 2, ObjErrorKind::MissingCoordinate),
        (b"vt 0 0 0 0\n", 1, ObjErrorKind::TooManyNumbers),
        (b"vt nan 0\n", 1, ObjErrorKind::BadNumber),
        (b"vn 0 0\n", 1, ObjErrorKind::MissingCoordinate),
        (b"\nvn 0 0 1 0\n", 2, ObjErrorKind::TooManyNumbers),
        (b"vn 0 inf 1\n", 1, ObjErrorKind::BadNumber),
    ];
    for (bytes, line, kind) in cases {
        let first_error = ObjReader::<4>::new(bytes).find_map(Result::err);
        assert_eq!(
            first_error,
            Some(at(line, kind)),
            "{}",
            String::from_utf8_lossy(bytes)
        );
        assert_eq!(count(bytes), Err(at(line, kind)));
    }
}
