//! What a picture shows: the raster layer, paths, highlighted PoIs, size, legend.

/// Which layer the raster shows.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum RasterLayer {
    /// Traversability when the world has it, elevation otherwise.
    #[default]
    Auto,
    /// The elevation (light = low, dark = high).
    Elevation,
    /// The traversability (green = 1, red = 0); falls back to elevation without one.
    Traversability,
}

/// What to draw and how big.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderOptions {
    /// Title above the map.
    pub title: Option<String>,
    /// Polylines of world points `[x, y]` drawn over the map (e.g. a plan's paths).
    pub paths: Vec<Vec<[f64; 2]>>,
    /// SVG colour of each path (e.g. one per robot of a team); the default colour for
    /// paths without one.
    pub path_colours: Vec<String>,
    /// PoIs to emphasise, as `(target index, PoI index)` in the world's mission.
    pub highlighted_pois: Vec<(usize, usize)>,
    /// The layer shown as raster.
    pub layer: RasterLayer,
    /// Length of the map's longer side in the picture, pixels.
    pub map_size_px: f64,
    /// Draw the legend beside the map.
    pub legend: bool,
    /// Draw the scale bar under the map.
    pub scale_bar: bool,
}

impl Default for RenderOptions {
    fn default() -> Self {
        Self {
            title: None,
            paths: Vec::new(),
            path_colours: Vec::new(),
            highlighted_pois: Vec::new(),
            layer: RasterLayer::Auto,
            map_size_px: 800.0,
            legend: true,
            scale_bar: true,
        }
    }
}
