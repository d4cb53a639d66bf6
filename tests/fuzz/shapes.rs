//! Whole scenes built from the edge cases of each field: a torus whose tube is as wide as
//! the ring, zero and 1e30 sizes, zero scale, a field of view of 0° or 180°, a camera at its
//! target, zero and subnormal directions, a spot whose inner angle passes its outer one.

use crate::random::Random;

/// Floats at the edges, as RON writes them.
const EDGES: &[&str] = &[
    "0.0",
    "-0.0",
    "1.0",
    "-1.0",
    "1e-45",
    "1e-30",
    "1e30",
    "3.4028235e38",
    "NaN",
    "inf",
    "-inf",
    "0.5",
    "2.0",
];

/// Sizes: zero, subnormal, ordinary, huge, invalid.
const SIZES: &[&str] = &[
    "0.0", "1e-45", "1e-6", "1.0", "1e6", "1e30", "-1.0", "NaN", "inf",
];

/// Angles in degrees.
const ANGLES: &[&str] = &[
    "0.0", "1e-6", "12.5", "17.5", "89.9", "90.0", "179.0", "180.0", "360.0", "1e9", "inf", "NaN",
    "-5.0",
];

fn pick_float(random: &mut Random, pool: &[&str]) -> String {
    random.pick(pool).to_string()
}

fn vector(random: &mut Random, pool: &[&str]) -> String {
    let [x, y, z] = [0; 3].map(|_| pick_float(random, pool));
    format!("({x}, {y}, {z})")
}

/// A direction: zero, subnormal, tiny, huge, ordinary or invalid; only valid ones where not
/// `hostile`.
fn direction(random: &mut Random, hostile: bool) -> String {
    if !hostile {
        let valid = [
            "(1e-30, -1e-30, 0.0)",
            "(3e38, 3e38, 3e38)",
            "(-3.4028235e38, 3.4028235e38, 0.0)",
            "(0.0, -1.0, 0.0)",
            "(-1.0, -1.0, -0.5)",
        ];
        return random.pick(&valid).to_string();
    }
    let special = [
        "(0.0, 0.0, 0.0)",
        "(1e-30, -1e-30, 0.0)",
        "(1e-45, 0.0, 0.0)",
        "(3e38, 3e38, 3e38)",
        "(-3.4028235e38, 3.4028235e38, 0.0)",
        "(0.0, -1.0, 0.0)",
        "(0.0, 1.0, 0.0)",
        "(-1.0, -1.0, -0.5)",
        "(NaN, 0.0, 0.0)",
    ];
    if random.one_in(3) {
        vector(random, EDGES)
    } else {
        random.pick(&special).to_string()
    }
}

fn color(random: &mut Random, hostile: bool) -> String {
    let f = |random: &mut Random| pick_float(random, EDGES);
    match random.below(6) {
        0 => format!("Srgb({}, {}, {})", f(random), f(random), f(random)),
        1 => format!(
            "Srgba({}, {}, {}, {})",
            f(random),
            f(random),
            f(random),
            f(random)
        ),
        2 => format!("Linear({}, {}, {})", f(random), f(random), f(random)),
        3 => format!(
            "Hex({:?})",
            if hostile {
                random.pick(&["#fff", "#ffcc00", "#ffcc0080", "#12345", "", "#gggggg"])
            } else {
                random.pick(&["#fff", "#ffcc00", "#ffcc0080"])
            }
        ),
        4 => "Linear(3.4028235e38, 3.4028235e38, 3.4028235e38)".into(),
        _ => "Srgba(1.0, 1.0, 1.0, NaN)".into(),
    }
}

fn decay(random: &mut Random) -> String {
    let f = |random: &mut Random| pick_float(random, EDGES);
    format!(
        "(constant: {}, linear: {}, quadratic: {})",
        f(random),
        f(random),
        f(random)
    )
}

/// A position: any edge value where `hostile`, else an ordinary or far one.
fn position(random: &mut Random, hostile: bool) -> String {
    if hostile {
        vector(random, EDGES)
    } else {
        vector(random, &["0.0", "1.0", "-2.0", "1e-30", "1e5", "-1e30"])
    }
}

fn light(random: &mut Random, hostile: bool) -> String {
    let range = match random.below(3) {
        0 => "None".to_owned(),
        _ => format!("Some({})", pick_float(random, SIZES)),
    };
    match random.below(3) {
        0 => format!(
            "Directional(color: {}, direction: {})",
            color(random, hostile),
            direction(random, hostile)
        ),
        1 => format!(
            "Point(color: {}, specular: Some({}), position: {}, decay: {}, range: {range})",
            color(random, hostile),
            color(random, hostile),
            position(random, hostile),
            decay(random),
        ),
        _ => format!(
            "Spot(color: {}, position: {}, direction: {}, decay: {}, range: {range}, \
             inner_angle_degrees: {}, outer_angle_degrees: {}, exponent: {})",
            color(random, hostile),
            position(random, hostile),
            direction(random, hostile),
            decay(random),
            pick_float(random, ANGLES),
            pick_float(random, ANGLES),
            pick_float(random, EDGES),
        ),
    }
}

fn mesh(random: &mut Random, hostile: bool) -> String {
    let sizes = if hostile {
        SIZES
    } else {
        &["1e-6", "1.0", "2.5", "1e6"]
    };
    let s = |random: &mut Random| pick_float(random, sizes);
    match random.below(7) {
        0 => format!("Sphere(radius: {})", s(random)),
        1 => format!(
            "Cuboid(size: ({}, {}, {}))",
            s(random),
            s(random),
            s(random)
        ),
        2 => format!("Plane(size: ({}, {}))", s(random), s(random)),
        3 => {
            // The tube as wide as the ring, wider, or narrower.
            let minor = s(random);
            let major = match random.below(3) {
                0 => minor.clone(),
                _ => s(random),
            };
            format!("Torus(minor_radius: {minor}, major_radius: {major})")
        }
        4 => format!("Cylinder(radius: {}, height: {})", s(random), s(random)),
        5 => format!("Capsule(radius: {}, length: {})", s(random), s(random)),
        _ => format!("Cone(radius: {}, height: {})", s(random), s(random)),
    }
}

fn material(random: &mut Random, hostile: bool) -> String {
    let f = |random: &mut Random| pick_float(random, EDGES);
    let alpha_mode = match random.below(3) {
        0 => "Opaque".to_owned(),
        1 => format!("Mask({})", f(random)),
        _ => "Blend".to_owned(),
    };
    format!(
        "Inline((base_color: {}, specular_color: {}, emissive: {}, shininess: {}, \
         specular_strength: {}, ambient_factor: {}, alpha_mode: {alpha_mode}))",
        color(random, hostile),
        color(random, hostile),
        color(random, hostile),
        f(random),
        f(random),
        f(random),
    )
}

fn object(random: &mut Random, hostile: bool) -> String {
    let scale = match random.below(4) {
        0 => "(0.0, 0.0, 0.0)".to_owned(),
        1 => "(1e-30, 1e-30, 1e-30)".to_owned(),
        2 => "(1e30, 1e30, 1e30)".to_owned(),
        _ => position(random, hostile),
    };
    format!(
        "(mesh: {}, transform: (translation: {}, rotation: {}, scale: {scale}), material: {})",
        mesh(random, hostile),
        position(random, hostile),
        position(random, hostile),
        material(random, hostile),
    )
}

fn camera(random: &mut Random, hostile: bool) -> String {
    if !hostile {
        let fov = pick_float(random, &["1e-6", "45.0", "179.99"]);
        return format!("Some((position: (1e-30, 0.0, 5.0), fov_degrees: {fov}))");
    }
    let position = vector(random, EDGES);
    let looking_at = if random.one_in(3) {
        position.clone()
    } else {
        vector(random, EDGES)
    };
    let fov = pick_float(
        random,
        &["0.0", "1e-45", "45.0", "179.99", "180.0", "NaN", "-10.0"],
    );
    format!("Some((position: {position}, looking_at: {looking_at}, fov_degrees: {fov}))")
}

/// A scene of edge cases: a camera, the ambient light, up to four lights and three objects.
/// Half of them keep to values a scene file accepts where it checks them (camera, positions,
/// directions, sizes, transforms), so that they load and their light and material values
/// reach validation; the other half put edge values everywhere.
pub fn scene(random: &mut Random) -> String {
    let hostile = random.one_in(2);
    let lights: Vec<String> = (0..random.below(5))
        .map(|_| light(random, hostile))
        .collect();
    let objects: Vec<String> = (0..random.below(4))
        .map(|_| object(random, hostile))
        .collect();
    format!(
        "(camera: {}, ambient: Some({}), lights: [{}], objects: [{}])",
        camera(random, hostile),
        color(random, hostile),
        lights.join(", "),
        objects.join(", ")
    )
}
