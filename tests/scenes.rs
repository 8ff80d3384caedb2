//! Exact expected pixels for small hand-built scenes. Corners are on whole
//! pixel corners unless noted, so pixel `(i, j)` (sampled at `i + 0.5,
//! j + 0.5`) is inside a rectangle `[x0, x1) x [y0, y1)` exactly when
//! `x0 <= i < x1` and `y0 <= j < y1`.

mod common;

use common::{art, capture, vtx};
use zline::{Admission, Depth16, Depth24, DepthFormat, Renderer};
use zline::{ScanArrays, TableArrays};

type Small<D> = Renderer<TableArrays<u32, 64, 16, 64>, ScanArrays<u32, D, 16, 16, 64>>;

fn rect(x0: f32, y0: f32, x1: f32, y1: f32, z: f32) -> [zline::ScreenVertex; 4] {
    [
        vtx(x0, y0, z),
        vtx(x1, y0, z),
        vtx(x1, y1, z),
        vtx(x0, y1, z),
    ]
}

fn render<D: DepthFormat>(height: u16, polygons: &[(&[zline::ScreenVertex], u32)]) -> String {
    let mut renderer: Small<D> = Renderer::with_height(height, 0).unwrap();
    for (corners, color) in polygons {
        let admission = renderer.push_polygon_vertices(corners, *color).unwrap();
        assert!(matches!(admission, Admission::Queued(_)), "{admission:?}");
    }
    capture(&mut renderer).0.art("ABCDEFGHIJKLMNOPQRSTUVWXYZ")
}

/// Two overlapping polygons, the textbook figure: a rectangle and a right
/// triangle (hypotenuse x = y + 4), each in front in turn, each drawn first
/// in turn.
#[test]
fn two_overlapping_polygons() {
    let tri = |z| [vtx(6.0, 2.0, z), vtx(14.0, 2.0, z), vtx(14.0, 10.0, z)];
    let (near, far) = (0.25, 0.75);

    let rect_in_front = art("
        ................
        .AAAAAAA........
        .AAAAAAABBBBBB..
        .AAAAAAABBBBBB..
        .AAAAAAABBBBBB..
        .AAAAAAA.BBBBB..
        ..........BBBB..
        ...........BBB..
        ............BB..
        .............B..
        ................
    ");
    let triangle_in_front = art("
        ................
        .AAAAAAA........
        .AAAAABBBBBBBB..
        .AAAAAABBBBBBB..
        .AAAAAAABBBBBB..
        .AAAAAAA.BBBBB..
        ..........BBBB..
        ...........BBB..
        ............BB..
        .............B..
        ................
    ");
    let a_near = rect(1.0, 1.0, 8.0, 6.0, near);
    let a_far = rect(1.0, 1.0, 8.0, 6.0, far);
    let (b_near, b_far) = (tri(near), tri(far));
    for (a, b, expected) in [
        (&a_near, &b_far, &rect_in_front),
        (&a_far, &b_near, &triangle_in_front),
    ] {
        // Drawing order must not matter; colours stay A for the rectangle.
        let forward = render::<Depth16>(11, &[(a, 1), (b, 2)]);
        let backward = render::<Depth24>(11, &[(b, 2), (a, 1)]);
        assert_eq!(&forward, expected);
        assert_eq!(&backward, expected);
    }
}

/// Two triangles that pass through each other. P: z = 1/2 + (x - 8)/128,
/// Q: z = 1/2 + (y - 4)/64; they meet on the line x = 2y, so P is nearer
/// exactly where the sample has x < 2y, i.e. `i <= 2j`.
#[test]
fn interpenetrating_triangles_meet_on_the_line_x_equals_2y() {
    let zp = |x: f32| 0.5 + (x - 8.0) / 128.0;
    let zq = |y: f32| 0.5 + (y - 4.0) / 64.0;
    let p = [
        vtx(-4.0, -4.0, zp(-4.0)),
        vtx(40.0, -4.0, zp(40.0)),
        vtx(-4.0, 40.0, zp(-4.0)),
    ];
    let q = [
        vtx(-4.0, -4.0, zq(-4.0)),
        vtx(40.0, -4.0, zq(-4.0)),
        vtx(-4.0, 24.0, zq(24.0)),
    ];
    let expected = art("
        PQQQQQQQQQQQQQQQ
        PPPQQQQQQQQQQQQQ
        PPPPPQQQQQQQQQQQ
        PPPPPPPQQQQQQQQQ
        PPPPPPPPPQQQQQQQ
        PPPPPPPPPPPQQQQQ
        PPPPPPPPPPPPPQQQ
        PPPPPPPPPPPPPPPQ
    ");
    let p_color = u32::from(b'P' - b'A') + 1;
    let q_color = u32::from(b'Q' - b'A') + 1;
    assert_eq!(
        render::<Depth16>(8, &[(&p, p_color), (&q, q_color)]),
        expected
    );
    assert_eq!(
        render::<Depth24>(8, &[(&q, q_color), (&p, p_color)]),
        expected
    );
}

/// A concave 8-gon: a U with a notch [5, 9) x [1, 6) cut from the top.
#[test]
fn concave_u_shape() {
    let u = [
        vtx(1.0, 1.0, 0.5),
        vtx(5.0, 1.0, 0.5),
        vtx(5.0, 6.0, 0.5),
        vtx(9.0, 6.0, 0.5),
        vtx(9.0, 1.0, 0.5),
        vtx(13.0, 1.0, 0.5),
        vtx(13.0, 9.0, 0.5),
        vtx(1.0, 9.0, 0.5),
    ];
    let expected = art("
        ................
        .AAAA....AAAA...
        .AAAA....AAAA...
        .AAAA....AAAA...
        .AAAA....AAAA...
        .AAAA....AAAA...
        .AAAAAAAAAAAA...
        .AAAAAAAAAAAA...
        .AAAAAAAAAAAA...
        ................
    ");
    assert_eq!(render::<Depth16>(10, &[(&u, 1)]), expected);
    // The same outline, wound the other way and starting elsewhere.
    let mut reversed = u;
    reversed.reverse();
    reversed.rotate_left(3);
    assert_eq!(render::<Depth24>(10, &[(&reversed, 1)]), expected);
}

/// Concave with slanted edges: an arrow head; its rows are checked against
/// the independent even-odd reference, plus a few hand-checked pixels.
#[test]
fn concave_arrow_matches_reference() {
    let arrow = [
        vtx(2.0, 2.0, 0.3),
        vtx(14.0, 7.5, 0.3),
        vtx(2.0, 13.0, 0.3),
        vtx(6.0, 7.5, 0.3),
    ];
    let mut renderer: Small<Depth16> = Renderer::with_height(16, 0).unwrap();
    renderer.push_polygon_vertices(&arrow, 1).unwrap();
    let frame = capture(&mut renderer).0;
    for j in 0..16 {
        for i in 0..16 {
            let expected = common::covers(&arrow, i, j);
            assert_eq!(
                frame.color(i as usize, j as usize) == 1,
                expected,
                "({i}, {j})"
            );
        }
    }
    // Inside the notch (x < 6 on the middle row) is empty; the tip is full.
    assert_eq!(frame.color(4, 7), 0);
    assert_eq!(frame.color(7, 7), 1);
    assert_eq!(frame.color(12, 7), 1);
}

/// Rectangles crossing each side of the frame, then a far triangle whose
/// corners lie beyond all four sides behind them.
#[test]
fn polygons_crossing_every_screen_side() {
    let left = rect(-5.0, 1.0, 3.0, 3.0, 0.2);
    let top = rect(5.0, -4.0, 7.0, 2.0, 0.2);
    let right = rect(9.0, 3.0, 40.0, 5.0, 0.2);
    let bottom = rect(2.0, 6.0, 5.0, 15.0, 0.2);
    let back = [
        vtx(-30.0, -30.0, 0.9),
        vtx(60.0, -10.0, 0.9),
        vtx(0.0, 60.0, 0.9),
    ];
    let sides = art("
        .....TT.........
        LLL..TT.........
        LLL.............
        .........RRRRRRR
        .........RRRRRRR
        ................
        ..BBB...........
        ..BBB...........
    ");
    let color = |c: u8| u32::from(c - b'A') + 1;
    let scene = [
        (&left[..], color(b'L')),
        (&top[..], color(b'T')),
        (&right[..], color(b'R')),
        (&bottom[..], color(b'B')),
    ];
    assert_eq!(render::<Depth16>(8, &scene), sides);
    let mut with_back = scene.to_vec();
    with_back.push((&back[..], color(b'G')));
    assert_eq!(render::<Depth24>(8, &with_back), sides.replace('.', "G"));
}

/// Coplanar faces: on exactly equal depth the polygon added first keeps
/// the pixel, whatever rows the polygons start on and whatever order the
/// scanner meets them in (so the winner cannot change as a camera moves and
/// their first rows pass each other).
#[test]
fn coplanar_faces_first_added_wins() {
    let upper = rect(2.0, 1.0, 10.0, 5.0, 0.5);
    let lower = rect(6.0, 3.0, 14.0, 7.0, 0.5);
    let upper_wins = art("
        ................
        ..AAAAAAAA......
        ..AAAAAAAA......
        ..AAAAAAAABBBB..
        ..AAAAAAAABBBB..
        ......BBBBBBBB..
        ......BBBBBBBB..
        ................
    ");
    let lower_wins = art("
        ................
        ..AAAAAAAA......
        ..AAAAAAAA......
        ..AAAABBBBBBBB..
        ..AAAABBBBBBBB..
        ......BBBBBBBB..
        ......BBBBBBBB..
        ................
    ");
    for depth16 in [true, false] {
        let render = |scene: &[(&[zline::ScreenVertex], u32)]| {
            if depth16 {
                render::<Depth16>(8, scene)
            } else {
                render::<Depth24>(8, scene)
            }
        };
        assert_eq!(render(&[(&upper, 1), (&lower, 2)]), upper_wins);
        assert_eq!(render(&[(&lower, 2), (&upper, 1)]), lower_wins);
        // The same when both start on one row.
        let tall = rect(6.0, 1.0, 14.0, 7.0, 0.5);
        let a_first = art("
            ................
            ..AAAAAAAABBBB..
            ..AAAAAAAABBBB..
            ..AAAAAAAABBBB..
            ..AAAAAAAABBBB..
            ......BBBBBBBB..
            ......BBBBBBBB..
            ................
        ");
        let b_first = art("
            ................
            ..AAAABBBBBBBB..
            ..AAAABBBBBBBB..
            ..AAAABBBBBBBB..
            ..AAAABBBBBBBB..
            ......BBBBBBBB..
            ......BBBBBBBB..
            ................
        ");
        assert_eq!(render(&[(&upper, 1), (&tall, 2)]), a_first);
        assert_eq!(render(&[(&tall, 2), (&upper, 1)]), b_first);
    }
}
