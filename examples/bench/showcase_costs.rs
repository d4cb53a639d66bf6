//! The showcase's tables: the cost of shadows (`--shadows`), of each group of material
//! features (`--materials`) and of each stylized mode (`--stylized`), each row measured
//! over rounds in which the rows take turns.

use crate::scene::{Scene, Shading};
use crate::timing::{median_frame_time, median_frame_time_and_picture};
use crate::{Options, ablation, alternating_medians, features, ms, write};
use bevy_phong::SpecularModel;
use std::{fmt::Write as _, path::Path};

/// The rows of the shadow table: Phong and Standard, each without shadows, with them, and
/// with them in a split screen.
pub const SHADOW_ROWS: usize = 6;
/// The groups of material features, the plain showcase first.
const GROUPS: usize = 6;
/// The rows of the material table: each group, Phong then Standard.
pub const MATERIAL_ROWS: usize = 2 * GROUPS;
/// The rows of the stylized table: the default material, then each mode.
pub const STYLIZED_ROWS: usize = 9;

/// The cost of shadows: the showcase on a floor with its lights casting shadows or not, and
/// casting them into a split screen (two cameras side by side, each with cascades of its
/// own), Phong beside `StandardMaterial`, all measured in this run.
pub fn shadow_costs(options: &Options, directory: &Path) {
    let size = options.shadow_size;
    let phong = Shading::Phong(Some(SpecularModel::Phong));
    let mut csv = String::from("size,shading,shadows,split_screen,round,median_ms\n");
    let rows: [_; SHADOW_ROWS] = [
        ("Phong", phong, false, false),
        ("Phong", phong, true, false),
        ("Phong", phong, true, true),
        ("Standard", Shading::Standard, false, false),
        ("Standard", Shading::Standard, true, false),
        ("Standard", Shading::Standard, true, true),
    ];
    let times: [f64; SHADOW_ROWS] = alternating_medians(options.rounds, |row, round| {
        let (name, shading, shadows, split_screen) = rows[row];
        let scene = Scene::ShowcaseOnFloor {
            shadows,
            split_screen,
        };
        let median = ms(median_frame_time(
            scene,
            size,
            shading,
            options.culling,
            options.frames,
        ));
        let _ = writeln!(
            csv,
            "{size},{name},{shadows},{split_screen},{round},{median:.3}"
        );
        crate::measured!(
            "{} {size}² {name}, round {round}: {median:.1} ms",
            scene.name()
        );
        median
    });
    let [
        phong_off,
        phong_on,
        phong_split,
        standard_off,
        standard_on,
        standard_split,
    ] = times;
    let table = format!(
        "| size | cameras | Phong | Phong, shadows | Standard | Standard, shadows | Phong shadows / Standard shadows | Phong shadows / Phong |\n\
         |---|---|---|---|---|---|---|---|\n\
         | {size}² | one | {phong_off:.1} | {phong_on:.1} | {standard_off:.1} | {standard_on:.1} | {:.2} | {:.2} |\n\
         | {size}² | two side by side | | {phong_split:.1} | | {standard_split:.1} | {:.2} | |\n\
         \n\
         Split screen over one camera, shadows on: Phong {:.2}, Standard {:.2}.\n",
        phong_on / standard_on,
        phong_on / phong_off,
        phong_split / standard_split,
        phong_split / phong_on,
        standard_split / standard_on,
    );
    println!(
        "\nShadows, median ms (the median of {} rounds): the showcase on a floor, a cascaded directional light and two \
         point lights casting shadows or not (1024² maps), seen by one camera or by two side by side (each drawing half \
         the picture, each with cascades of its own):\n\n{table}",
        options.rounds
    );
    write(&directory.join("shadows.csv"), &csv);
}

/// The showcase with each group of material features beside the plain showcase, Phong and
/// Standard (with the nearest settings Bevy has), at the shadow table's size, the rows
/// taking turns over the rounds.
pub fn material_costs(options: &Options, directory: &Path) {
    let size = options.shadow_size;
    let phong = Shading::Phong(Some(SpecularModel::Phong));
    let groups: [_; GROUPS] = [
        None,
        Some(features::Features::SurfaceInputs),
        Some(features::Features::BakedLight),
        Some(features::Features::Environment),
        Some(features::Features::Converted),
        Some(features::Features::ConvertedEnvironment),
    ];
    let scene = |group: Option<features::Features>| group.map_or(Scene::Showcase, Scene::Featured);
    let mut csv = String::from("size,scene,shading,round,median_ms\n");
    // Each row's picture (from its first round), to show that its features are drawn.
    let mut pictures: [Vec<u8>; MATERIAL_ROWS] = [const { Vec::new() }; MATERIAL_ROWS];
    let times: [f64; MATERIAL_ROWS] = alternating_medians(options.rounds, |row, round| {
        let (name, shading) = if row < GROUPS {
            ("Phong", phong)
        } else {
            ("Standard", Shading::Standard)
        };
        let scene = scene(groups[row % GROUPS]);
        let (median, picture) = median_frame_time_and_picture(
            scene,
            size,
            shading,
            options.culling,
            options.frames,
            &[],
        );
        let median = ms(median);
        if round == 0 {
            pictures[row] = picture;
        }
        let _ = writeln!(csv, "{size},{},{name},{round},{median:.3}", scene.name());
        crate::measured!(
            "{} {size}² {name}, round {round}: {median:.1} ms",
            scene.name()
        );
        median
    });
    let mut table = String::from(
        "| scene | Phong ms | Standard ms | Phong / Standard | Phong / plain Phong | Standard / plain Standard | pixels changed, Phong / Standard |\n|---|---|---|---|---|---|---|\n",
    );
    for (row, group) in groups.iter().enumerate() {
        let (phong, standard) = (times[row], times[GROUPS + row]);
        let _ = writeln!(
            table,
            "| {} | {phong:.1} | {standard:.1} | {:.2} | {:.2} | {:.2} | {:.0} % / {:.0} % |",
            scene(*group).name(),
            phong / standard,
            phong / times[0],
            standard / times[GROUPS],
            ablation::changed_percent(&pictures[0], &pictures[row]),
            ablation::changed_percent(&pictures[GROUPS], &pictures[GROUPS + row]),
        );
    }
    println!(
        "\nMaterial features, median ms at {size}² (the median of {} rounds):\n\n{table}",
        options.rounds
    );
    write(&directory.join("materials.csv"), &csv);
}

/// The showcase drawn with each stylized mode beside the default material, Phong only, at
/// the shadow table's size, the rows taking turns over the rounds.
pub fn stylized_costs(options: &Options, directory: &Path) {
    use features::Features;
    let size = options.shadow_size;
    let modes: [_; STYLIZED_ROWS] = [
        None,
        Some(Features::Wrap),
        Some(Features::ToonBands),
        Some(Features::ToonRamp),
        Some(Features::ToonHighlight),
        Some(Features::Rim),
        Some(Features::RimLitSide),
        Some(Features::Hemisphere),
        Some(Features::Cookies),
    ];
    let scene = |mode: Option<Features>| mode.map_or(Scene::Showcase, Scene::Featured);
    let phong = Shading::Phong(Some(SpecularModel::Phong));
    let mut csv = String::from("size,scene,round,median_ms\n");
    let mut pictures: [Vec<u8>; STYLIZED_ROWS] = [const { Vec::new() }; STYLIZED_ROWS];
    let times: [f64; STYLIZED_ROWS] = alternating_medians(options.rounds, |row, round| {
        let scene = scene(modes[row]);
        let (median, picture) =
            median_frame_time_and_picture(scene, size, phong, options.culling, options.frames, &[]);
        let median = ms(median);
        if round == 0 {
            pictures[row] = picture;
        }
        let _ = writeln!(csv, "{size},{},{round},{median:.3}", scene.name());
        crate::measured!(
            "{} {size}² Phong, round {round}: {median:.1} ms",
            scene.name()
        );
        median
    });
    let mut table =
        String::from("| scene | Phong ms | × the default | pixels changed |\n|---|---|---|---|\n");
    for (row, mode) in modes.iter().enumerate() {
        let _ = writeln!(
            table,
            "| {} | {:.1} | {:.2} | {:.0} % |",
            scene(*mode).name(),
            times[row],
            times[row] / times[0],
            ablation::changed_percent(&pictures[0], &pictures[row]),
        );
    }
    println!(
        "\nStylized modes, median ms at {size}² (the median of {} rounds):\n\n{table}",
        options.rounds
    );
    write(&directory.join("stylized.csv"), &csv);
}
