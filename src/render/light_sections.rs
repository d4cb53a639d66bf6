//! The light buffer's sections, declared once: the built-in lights' records follow the
//! header in the order of [`LightSection::ALL`], each section's length counted in the
//! header ([`GpuLightsHeader`]). The gather writes the counts, the clusters and the scene
//! texture find the sections through [`GpuLightsHeader::range`], and the shaders read each
//! count through the accessor of `scene.wesl` that [`LightSection::count_name`] names (the
//! tests below check the header's fields and the shaders' accessors against this order).

use super::gpu_types::GpuLightsHeader;
use core::ops::Range;

/// A section of the light buffer.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum LightSection {
    /// Directional lights: every fragment loops over them.
    Directional,
    /// Local lights (point, spot) of unlimited reach: every fragment loops over them.
    Local,
    /// Local lights of finite reach: fragments find them through their view's clusters.
    ClusteredLocal,
    /// Area lights (rectangle, disk: [`GpuAreaLight`](crate::light_kind::GpuAreaLight)
    /// records) of unlimited reach.
    Area,
    /// Area lights of finite reach, found through the clusters.
    ClusteredArea,
}

impl LightSection {
    /// Every section, in the order of their records in the buffer.
    pub(crate) const ALL: [Self; 5] = [
        Self::Directional,
        Self::Local,
        Self::ClusteredLocal,
        Self::Area,
        Self::ClusteredArea,
    ];

    /// The name of its count: the header's field (in Rust and in `types.wesl`) and the
    /// accessor `scene.wesl` reads it with (what the tests check the shaders against).
    #[cfg(test)]
    const fn count_name(self) -> &'static str {
        match self {
            Self::Directional => "directional_count",
            Self::Local => "local_count",
            Self::ClusteredLocal => "clustered_local_count",
            Self::Area => "area_count",
            Self::ClusteredArea => "clustered_area_count",
        }
    }

    /// Whether its lights are found through the clusters.
    pub(crate) const fn is_clustered(self) -> bool {
        matches!(self, Self::ClusteredLocal | Self::ClusteredArea)
    }
}

impl GpuLightsHeader {
    /// The number of lights in `section`.
    pub(crate) fn count(&self, section: LightSection) -> u32 {
        *self.count_field(section)
    }

    /// The number of lights in `section`, to set.
    pub(crate) fn count_mut(&mut self, section: LightSection) -> &mut u32 {
        match section {
            LightSection::Directional => &mut self.directional_count,
            LightSection::Local => &mut self.local_count,
            LightSection::ClusteredLocal => &mut self.clustered_local_count,
            LightSection::Area => &mut self.area_count,
            LightSection::ClusteredArea => &mut self.clustered_area_count,
        }
    }

    fn count_field(&self, section: LightSection) -> &u32 {
        match section {
            LightSection::Directional => &self.directional_count,
            LightSection::Local => &self.local_count,
            LightSection::ClusteredLocal => &self.clustered_local_count,
            LightSection::Area => &self.area_count,
            LightSection::ClusteredArea => &self.clustered_area_count,
        }
    }

    /// The records of `section`: indices into the array of records after the header.
    pub(crate) fn range(&self, section: LightSection) -> Range<usize> {
        let start: u32 = LightSection::ALL
            .into_iter()
            .take_while(|&before| before != section)
            .map(|before| self.count(before))
            .sum();
        start as usize..(start + self.count(section)) as usize
    }

    /// The records from the start of `first` to the end of `last`.
    pub(crate) fn span(&self, first: LightSection, last: LightSection) -> Range<usize> {
        self.range(first).start..self.range(last).end
    }

    /// Every section's count, in [`LightSection::ALL`]'s order.
    pub(crate) fn counts(&self) -> [u32; 5] {
        LightSection::ALL.map(|section| self.count(section))
    }

    /// Total number of lights in the array.
    pub fn light_count(&self) -> usize {
        self.counts().iter().sum::<u32>() as usize
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::{fs, path::Path};

    #[test]
    fn the_sections_follow_each_other_in_the_order_of_their_counts_in_the_header() {
        let mut header: GpuLightsHeader = bytemuck::Zeroable::zeroed();
        for (index, section) in LightSection::ALL.into_iter().enumerate() {
            *header.count_mut(section) = index as u32 + 1;
        }
        let mut end = 0;
        let mut offset = 0;
        for (index, section) in LightSection::ALL.into_iter().enumerate() {
            let range = header.range(section);
            assert_eq!(
                range.start, end,
                "{section:?} starts where the last one ends"
            );
            assert_eq!(range.len(), index + 1);
            end = range.end;
            // Its count's place in the header, as the shaders read it.
            let field = header.count_field(section) as *const u32 as usize;
            let field = field - (&header as *const GpuLightsHeader as usize);
            assert!(field > offset, "{section:?}'s count follows the last one's");
            offset = field;
        }
        assert_eq!(header.light_count(), end);
        assert_eq!(
            header.span(LightSection::Area, LightSection::ClusteredArea),
            6..15
        );
    }

    #[test]
    fn the_shaders_read_each_count_in_the_order_of_the_sections() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/shaders");
        let read = |file: &str| fs::read_to_string(root.join(file)).expect(file);
        let types = read("types.wesl");
        let fields = &types[types.find("struct PhongLights").expect("PhongLights")..];
        let scene = read("scene.wesl");
        let mut last = 0;
        for section in LightSection::ALL {
            let name = section.count_name();
            let at = fields
                .find(&format!("    {name}: u32,"))
                .unwrap_or_else(|| panic!("types.wesl's PhongLights has no field {name}"));
            assert!(at > last, "types.wesl: {name} out of the sections' order");
            last = at;
            // One accessor for each place the scene data can be bound in.
            let accessors = scene.matches(&format!("fn {name}() -> u32")).count();
            assert_eq!(accessors, 2, "scene.wesl's accessors of {name}");
        }
    }
}
