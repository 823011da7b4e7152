//! Real terrain inputs: GeoTIFF DEMs and point clouds (PLY, PCD) written by the tests
//! with values known by construction, read back, rasterised, and used by the `map` world.

use smug_core::{GridLayer, LoadedConfig, Pipeline};
use smug_worlds::geotiff::{read_geotiff, RasterType};
use smug_worlds::point_cloud::{rasterise, read_point_cloud, Reduce};
use std::path::{Path, PathBuf};
use tiff::encoder::{colortype, TiffEncoder};
use tiff::tags::Tag;

/// Writes a test file at the path it is given.
type Writer = Box<dyn Fn(&Path)>;

/// A fresh, empty folder for one test.
fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("terrain-{name}"));
    std::fs::remove_dir_all(&dir).ok();
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// How a test GeoTIFF is georeferenced.
enum Georef {
    /// ModelPixelScale (s, s) + ModelTiepoint (0, 0) ↦ (x, y).
    Tiepoint {
        scale: [f64; 2],
        at: [f64; 2],
    },
    /// ModelTransformation (a full 4 × 4 matrix, row-major).
    Matrix([f64; 16]),
    None,
}

/// Samples of a test GeoTIFF, top row first.
enum Samples {
    F32(Vec<f32>),
    F64(Vec<f64>),
    I16(Vec<i16>),
    Rgb(Vec<u8>),
}

fn write_geotiff(
    path: &Path,
    size: [u32; 2],
    samples: Samples,
    georef: Georef,
    point: bool,
    nodata: Option<&str>,
) {
    write_geotiff_coded(path, size, samples, georef, point, nodata, None);
}

/// Like [`write_geotiff`], LZW-compressed (with horizontal differencing when `predictor`).
#[allow(clippy::too_many_arguments)]
fn write_geotiff_coded(
    path: &Path,
    size: [u32; 2],
    samples: Samples,
    georef: Georef,
    point: bool,
    nodata: Option<&str>,
    lzw_predictor: Option<bool>,
) {
    let file = std::fs::File::create(path).unwrap();
    let mut tiff = TiffEncoder::new(std::io::BufWriter::new(file)).unwrap();
    if let Some(predictor) = lzw_predictor {
        tiff = tiff.with_compression(tiff::encoder::Compression::Lzw);
        if predictor {
            tiff = tiff.with_predictor(tiff::encoder::Predictor::Horizontal);
        }
    }
    macro_rules! write {
        ($colour:ty, $data:expr) => {{
            let mut image = tiff.new_image::<$colour>(size[0], size[1]).unwrap();
            let dir = image.encoder();
            match &georef {
                Georef::Tiepoint { scale, at } => {
                    dir.write_tag(Tag::ModelPixelScaleTag, &[scale[0], scale[1], 0.0][..])
                        .unwrap();
                    dir.write_tag(
                        Tag::ModelTiepointTag,
                        &[0.0, 0.0, 0.0, at[0], at[1], 0.0][..],
                    )
                    .unwrap();
                }
                Georef::Matrix(m) => dir.write_tag(Tag::ModelTransformationTag, &m[..]).unwrap(),
                Georef::None => {}
            }
            // GeoKeyDirectory: version 1.1.0, 2 keys: GTModelType = projected (1, or
            // geographic 2 for the `nodata` text "geographic"), GTRasterType = area (1)
            // or point (2).
            let raster = if point { 2u16 } else { 1 };
            let model = if nodata == Some("geographic") {
                2u16
            } else {
                1
            };
            let keys: [u16; 12] = [1, 1, 0, 2, 1024, 0, 1, model, 1025, 0, 1, raster];
            dir.write_tag(Tag::GeoKeyDirectoryTag, &keys[..]).unwrap();
            if let Some(nodata) = nodata {
                dir.write_tag(Tag::GdalNodata, nodata).unwrap();
            }
            image.write_data($data).unwrap();
        }};
    }
    match &samples {
        Samples::F32(v) => write!(colortype::Gray32Float, v),
        Samples::F64(v) => write!(colortype::Gray64Float, v),
        Samples::I16(v) => write!(colortype::GrayI16, v),
        Samples::Rgb(v) => write!(colortype::RGB8, v),
    }
}

/// Height of raster pixel (column c, row r) in the test DEMs.
fn known(c: usize, r: usize) -> f64 {
    c as f64 + 10.0 * r as f64 + 0.25
}

/// Checks cell (i, j) of a 4 × 3 DEM holds pixel (i, 2 − j).
fn assert_known_heights(layer: &GridLayer) {
    assert_eq!(layer.geometry.size, [4, 3]);
    for j in 0..3 {
        for i in 0..4 {
            let got = layer.data[layer.geometry.index(i, j)];
            assert_eq!(f64::from(got), known(i, 2 - j), "cell ({i}, {j})");
        }
    }
}

fn pixels<T>(f: impl Fn(f64) -> T) -> Vec<T> {
    (0..3)
        .flat_map(|r| (0..4).map(move |c| (c, r)))
        .map(|(c, r)| f(known(c, r)))
        .collect()
}

const TIE: Georef = Georef::Tiepoint {
    scale: [0.5, 0.5],
    at: [100.0, 50.0],
};

#[test]
fn float32_pixel_is_area_reads_heights_resolution_origin() {
    let dir = scratch("f32");
    let path = dir.join("dem.tif");
    write_geotiff(
        &path,
        [4, 3],
        Samples::F32(pixels(|z| z as f32)),
        TIE,
        false,
        None,
    );
    let dem = read_geotiff(&path).unwrap();
    assert_eq!(dem.raster_type, RasterType::PixelIsArea);
    let g = dem.elevation.geometry;
    assert_eq!(g.resolution, 0.5);
    // upper-left corner (100, 50); 3 rows of 0.5 m below it
    assert_eq!(g.origin, [100.0, 48.5]);
    assert_known_heights(&dem.elevation);
    // the pixel whose centre is (100.25, 49.75) is raster (0, 0)
    assert_eq!(
        dem.elevation.nearest(100.25, 49.75),
        Some(f64::from(known(0, 0) as f32))
    );
}

#[test]
fn float64_with_a_model_transformation() {
    let dir = scratch("f64");
    let path = dir.join("dem.tif");
    #[rustfmt::skip]
    let m = [
        0.5, 0.0, 0.0, 100.0,
        0.0, -0.5, 0.0, 50.0,
        0.0, 0.0, 0.0, 0.0,
        0.0, 0.0, 0.0, 1.0,
    ];
    write_geotiff(
        &path,
        [4, 3],
        Samples::F64(pixels(|z| z)),
        Georef::Matrix(m),
        false,
        None,
    );
    let dem = read_geotiff(&path).unwrap();
    assert_eq!(dem.elevation.geometry.origin, [100.0, 48.5]);
    assert_eq!(dem.elevation.geometry.resolution, 0.5);
    assert_known_heights(&dem.elevation);
}

#[test]
fn int16_with_nodata() {
    let dir = scratch("i16");
    let path = dir.join("dem.tif");
    let mut values: Vec<i16> = pixels(|z| z.floor() as i16);
    values[5] = -9999; // column 1, row 1
    write_geotiff(
        &path,
        [4, 3],
        Samples::I16(values),
        TIE,
        false,
        Some("-9999"),
    );
    let dem = read_geotiff(&path).unwrap();
    assert_eq!(dem.nodata, Some(-9999.0));
    let layer = &dem.elevation;
    let at = |c: usize, r: usize| layer.data[layer.geometry.index(c, 2 - r)];
    assert!(at(1, 1).is_nan());
    assert_eq!(at(0, 0), 0.0);
    assert_eq!(at(3, 2), 23.0);
    assert_eq!(layer.data.iter().filter(|v| v.is_nan()).count(), 1);
}

#[test]
fn lzw_compressed_dems_with_and_without_the_predictor() {
    let dir = scratch("lzw");
    for predictor in [false, true] {
        let path = dir.join(format!("i16-{predictor}.tif"));
        let values: Vec<i16> = pixels(|z| (z.floor() as i16) * 300 - 3000);
        let samples = Samples::I16(values);
        write_geotiff_coded(&path, [4, 3], samples, TIE, false, None, Some(predictor));
        let dem = read_geotiff(&path).unwrap();
        let l = &dem.elevation;
        assert_eq!(l.geometry.origin, [100.0, 48.5]);
        for (c, r) in [(0, 0), (3, 0), (1, 1), (3, 2)] {
            let want = (known(c, r).floor() * 300.0 - 3000.0) as f32;
            assert_eq!(
                l.data[l.geometry.index(c, 2 - r)],
                want,
                "{predictor} ({c}, {r})"
            );
        }
    }
    // (horizontal differencing is for integers)
    let path = dir.join("f32.tif");
    let samples = Samples::F32(pixels(|z| z as f32));
    write_geotiff_coded(&path, [4, 3], samples, TIE, false, None, Some(false));
    assert_known_heights(&read_geotiff(&path).unwrap().elevation);
}

#[test]
fn float32_nan_nodata_and_pixel_is_point() {
    let dir = scratch("point");
    let path = dir.join("dem.tif");
    let mut values = pixels(|z| z as f32);
    values[0] = f32::NAN;
    write_geotiff(&path, [4, 3], Samples::F32(values), TIE, true, Some("nan"));
    let dem = read_geotiff(&path).unwrap();
    assert_eq!(dem.raster_type, RasterType::PixelIsPoint);
    // raster (0, 0) is the centre of the upper-left pixel: its corner is half a pixel out
    assert_eq!(dem.elevation.geometry.origin, [99.75, 48.75]);
    assert_eq!(dem.elevation.nearest(100.0, 50.0), None); // NaN: no data
    assert!(dem.elevation.data[dem.elevation.geometry.index(0, 2)].is_nan());
    assert_eq!(
        dem.elevation.nearest(100.5, 50.0),
        Some(f64::from(known(1, 0) as f32))
    );
}

#[test]
fn bad_geotiffs_name_the_file_and_the_fault() {
    let dir = scratch("bad");
    let cases: Vec<(&str, Writer, &str)> = vec![
        (
            "nogeo.tif",
            Box::new(|p| {
                write_geotiff(
                    p,
                    [4, 3],
                    Samples::F32(pixels(|z| z as f32)),
                    Georef::None,
                    false,
                    None,
                )
            }),
            "no georeferencing",
        ),
        (
            "rgb.tif",
            Box::new(|p| write_geotiff(p, [4, 3], Samples::Rgb(vec![0; 36]), TIE, false, None)),
            "has 3 samples per pixel",
        ),
        (
            "oblong.tif",
            Box::new(|p| {
                let g = Georef::Tiepoint {
                    scale: [0.5, 0.25],
                    at: [0.0, 0.0],
                };
                write_geotiff(
                    p,
                    [4, 3],
                    Samples::F32(pixels(|z| z as f32)),
                    g,
                    false,
                    None,
                )
            }),
            "pixels are 0.5 × 0.25",
        ),
        (
            "rotated.tif",
            Box::new(|p| {
                let mut m = [0.0; 16];
                (m[0], m[1], m[4], m[5], m[15]) = (0.5, 0.1, 0.1, -0.5, 1.0);
                write_geotiff(
                    p,
                    [4, 3],
                    Samples::F32(pixels(|z| z as f32)),
                    Georef::Matrix(m),
                    false,
                    None,
                )
            }),
            "rotates or shears",
        ),
        (
            "badnodata.tif",
            Box::new(|p| {
                write_geotiff(
                    p,
                    [4, 3],
                    Samples::F32(pixels(|z| z as f32)),
                    TIE,
                    false,
                    Some("none"),
                )
            }),
            "GDAL_NODATA `none` is not a number",
        ),
        (
            "degrees.tif",
            Box::new(|p| {
                write_geotiff(
                    p,
                    [4, 3],
                    Samples::F32(pixels(|z| z as f32)),
                    TIE,
                    false,
                    Some("geographic"),
                )
            }),
            "is in geographic coordinates (degrees)",
        ),
        (
            "text.tif",
            Box::new(|p| std::fs::write(p, "not a tiff").unwrap()),
            "not a readable TIFF",
        ),
        (
            "truncated.tif",
            Box::new(|p| {
                write_geotiff(
                    p,
                    [4, 3],
                    Samples::F32(pixels(|z| z as f32)),
                    TIE,
                    false,
                    None,
                );
                let bytes = std::fs::read(p).unwrap();
                std::fs::write(p, &bytes[..bytes.len() / 3]).unwrap();
            }),
            "",
        ),
    ];
    for (name, write, needle) in cases {
        let path = dir.join(name);
        write(&path);
        let err = read_geotiff(&path).unwrap_err().to_string();
        assert!(err.starts_with(&path.display().to_string()), "{err}");
        assert!(err.contains(needle), "{name}: {err}");
    }
    let err = read_geotiff(&dir.join("missing.tif"))
        .unwrap_err()
        .to_string();
    assert!(err.contains("missing.tif: cannot read"), "{err}");
}

// --- point clouds ----------------------------------------------------------------------

const POINTS: [[f64; 3]; 5] = [
    [0.05, 0.05, 1.0],
    [0.15, 0.05, 3.0], // same 0.2 m cell as the first
    [0.35, 0.05, 2.0],
    [0.05, 0.45, -1.0],
    [0.05, 0.45, f64::NAN], // invalid: dropped
];

fn ply_header(format: &str, n: usize) -> String {
    format!(
        "ply\nformat {format} 1.0\ncomment written by the SMUG tests\nelement vertex {n}\n\
         property float x\nproperty float y\nproperty double z\nproperty uchar intensity\n\
         element face 1\nproperty list uchar int vertex_indices\nend_header\n"
    )
}

fn write_ply_binary(path: &Path, little: bool) {
    let mut bytes = ply_header(
        if little {
            "binary_little_endian"
        } else {
            "binary_big_endian"
        },
        POINTS.len(),
    )
    .into_bytes();
    for p in POINTS {
        let (x, y) = (p[0] as f32, p[1] as f32);
        if little {
            bytes.extend(x.to_le_bytes());
            bytes.extend(y.to_le_bytes());
            bytes.extend(p[2].to_le_bytes());
        } else {
            bytes.extend(x.to_be_bytes());
            bytes.extend(y.to_be_bytes());
            bytes.extend(p[2].to_be_bytes());
        }
        bytes.push(7);
    }
    bytes.push(3);
    for k in [0i32, 1, 2] {
        bytes.extend(if little {
            k.to_le_bytes()
        } else {
            k.to_be_bytes()
        });
    }
    std::fs::write(path, bytes).unwrap();
}

fn write_ply_ascii(path: &Path) {
    let mut text = ply_header("ascii", POINTS.len());
    for p in POINTS {
        text += &format!("{} {} {} 7\n", p[0] as f32, p[1] as f32, p[2]);
    }
    text += "3 0 1 2\n";
    std::fs::write(path, text).unwrap();
}

fn pcd_header(data: &str, n: usize) -> String {
    format!(
        "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS x y z rgb\n\
         SIZE 4 4 8 4\nTYPE F F F U\nCOUNT 1 1 1 1\nWIDTH {n}\nHEIGHT 1\n\
         VIEWPOINT 0 0 0 1 0 0 0\nPOINTS {n}\nDATA {data}\n"
    )
}

fn write_pcd(path: &Path, binary: bool) {
    let mut bytes = pcd_header(if binary { "binary" } else { "ascii" }, POINTS.len()).into_bytes();
    for p in POINTS {
        if binary {
            bytes.extend((p[0] as f32).to_le_bytes());
            bytes.extend((p[1] as f32).to_le_bytes());
            bytes.extend(p[2].to_le_bytes());
            bytes.extend(0xffu32.to_le_bytes());
        } else {
            let z = if p[2].is_nan() {
                "nan".to_string()
            } else {
                p[2].to_string()
            };
            bytes.extend(format!("{} {} {z} 255\n", p[0] as f32, p[1] as f32).into_bytes());
        }
    }
    std::fs::write(path, bytes).unwrap();
}

#[test]
fn ply_and_pcd_in_every_encoding_read_the_same_points() {
    let dir = scratch("clouds");
    let files: [(&str, Writer); 5] = [
        ("a.ply", Box::new(write_ply_ascii)),
        ("le.ply", Box::new(|p| write_ply_binary(p, true))),
        ("be.ply", Box::new(|p| write_ply_binary(p, false))),
        ("a.pcd", Box::new(|p| write_pcd(p, false))),
        ("b.pcd", Box::new(|p| write_pcd(p, true))),
    ];
    for (name, write) in files {
        let path = dir.join(name);
        write(&path);
        let points = read_point_cloud(&path).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(points.len(), 4, "{name}: the NaN point is dropped");
        for (got, want) in points.iter().zip(POINTS) {
            // binary files hold the f32 value, ASCII ones its shortest decimal
            assert!((got[0] - want[0]).abs() < 1e-7, "{name}: {got:?}");
            assert!((got[1] - want[1]).abs() < 1e-7, "{name}: {got:?}");
            assert_eq!(got[2], want[2], "{name}");
        }
    }
}

#[test]
fn rasterise_takes_the_max_or_mean_and_leaves_empty_cells_unknown() {
    let points: Vec<[f64; 3]> = POINTS[..4].to_vec();
    let path = Path::new("cloud.ply");
    let max = rasterise(&points, 0.2, Reduce::Max, path).unwrap();
    assert_eq!(max.geometry.origin, [0.0, 0.0]);
    assert_eq!(max.geometry.size, [2, 3]);
    let at = |l: &GridLayer, i, j| l.data[l.geometry.index(i, j)];
    assert_eq!(at(&max, 0, 0), 3.0);
    assert_eq!(at(&max, 1, 0), 2.0);
    assert_eq!(at(&max, 0, 2), -1.0);
    assert!(at(&max, 0, 1).is_nan() && at(&max, 1, 1).is_nan() && at(&max, 1, 2).is_nan());
    let mean = rasterise(&points, 0.2, Reduce::Mean, path).unwrap();
    assert_eq!(at(&mean, 0, 0), 2.0);
    // a grid-aligned origin: shifted clouds share cells
    let shifted: Vec<[f64; 3]> = points
        .iter()
        .map(|p| [p[0] - 1.0, p[1] + 0.4, p[2]])
        .collect();
    let g = rasterise(&shifted, 0.2, Reduce::Max, path)
        .unwrap()
        .geometry;
    assert_eq!(g.origin, [-1.0, 0.4]);
    let err = rasterise(&[], 0.2, Reduce::Max, path)
        .unwrap_err()
        .to_string();
    assert_eq!(err, "cloud.ply: has no valid points");
    let err = rasterise(&points, 0.0, Reduce::Max, path)
        .unwrap_err()
        .to_string();
    assert!(err.contains("cell_size must be > 0"), "{err}");
    let err = rasterise(&points, 1e-7, Reduce::Max, path)
        .unwrap_err()
        .to_string();
    assert!(err.contains("more than the"), "{err}");
}

#[test]
fn bad_point_clouds_name_the_file_and_the_fault() {
    let dir = scratch("bad-clouds");
    let good_ply = ply_header("ascii", 2);
    let cases: Vec<(&str, Vec<u8>, &str)> = vec![
        ("short.ply", format!("{good_ply}0 0 0 1\n").into_bytes(), "ends after 1 of 2 vertices"),
        ("nan.ply", format!("{good_ply}0 0 0 1\n0 x 0 1\n").into_bytes(), "not a number in `0 x 0 1`"),
        ("nofmt.ply", b"ply\nelement vertex 0\nend_header\n".to_vec(), "no `format` line"),
        ("noz.ply", b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n0 0\n".to_vec(), "no vertex property `z` (found: x, y)"),
        ("weird.ply", b"ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\nend_header\n".to_vec(), "line 4: unknown property type: `property quad x`"),
        ("noend.ply", b"ply\nformat ascii 1.0\n".to_vec(), "no `end_header` line"),
        ("trunc.ply", {
            let mut b = ply_header("binary_little_endian", 2).into_bytes();
            b.extend([0u8; 10]);
            b
        }, "ends in vertex 0 of 2"),
        ("comp.pcd", pcd_header("binary_compressed", 1).into_bytes(), "binary_compressed PCD is not supported"),
        ("short.pcd", {
            let mut b = pcd_header("binary", 2).into_bytes();
            b.extend([0u8; 20]);
            b
        }, "the binary body has 20 bytes; 2 points of 20 bytes need 40"),
        ("cols.pcd", format!("{}1 2 3\n", pcd_header("ascii", 1)).into_bytes(), "point 0: 3 values, the header's fields need 4"),
        ("other.xyz", b"1 2 3\n".to_vec(), "neither a PLY file"),
    ];
    for (name, bytes, needle) in cases {
        let path = dir.join(name);
        std::fs::write(&path, bytes).unwrap();
        let err = read_point_cloud(&path).unwrap_err().to_string();
        assert!(err.starts_with(&path.display().to_string()), "{err}");
        assert!(err.contains(needle), "{name}: {err}");
    }
}

// --- the same terrain as a DEM and as a point cloud -------------------------------------

fn terrain(x: f64, y: f64) -> f64 {
    0.3 * (x * 1.3).sin() + 0.2 * (0.7 * y).cos() + 0.05 * x
}

#[test]
fn a_dem_and_a_point_cloud_of_the_same_terrain_agree_within_a_cell() {
    let dir = scratch("same-terrain");
    let (res, nx, ny) = (0.25, 40u32, 30u32);
    // DEM: heights at pixel centres, upper-left corner (0, ny·res).
    let mut values = Vec::new();
    for r in 0..ny {
        for c in 0..nx {
            let (x, y) = ((c as f64 + 0.5) * res, (ny as f64 - r as f64 - 0.5) * res);
            values.push(terrain(x, y) as f32);
        }
    }
    let dem_path = dir.join("terrain.tif");
    let georef = Georef::Tiepoint {
        scale: [res, res],
        at: [0.0, ny as f64 * res],
    };
    write_geotiff(
        &dem_path,
        [nx, ny],
        Samples::F32(values),
        georef,
        false,
        None,
    );
    // Cloud: 5 × 5 samples per cell, binary PLY.
    let mut points = Vec::new();
    let step = res / 5.0;
    for j in 0..ny * 5 {
        for i in 0..nx * 5 {
            let (x, y) = ((i as f64 + 0.5) * step, (j as f64 + 0.5) * step);
            points.push([x, y, terrain(x, y)]);
        }
    }
    let cloud_path = dir.join("terrain.ply");
    let mut bytes = format!(
        "ply\nformat binary_little_endian 1.0\nelement vertex {}\nproperty double x\n\
         property double y\nproperty double z\nend_header\n",
        points.len()
    )
    .into_bytes();
    for p in &points {
        for v in p {
            bytes.extend(v.to_le_bytes());
        }
    }
    std::fs::write(&cloud_path, bytes).unwrap();

    let dem = read_geotiff(&dem_path).unwrap().elevation;
    let read = read_point_cloud(&cloud_path).unwrap();
    assert_eq!(read.len(), points.len());
    let cloud = rasterise(&read, res, Reduce::Mean, &cloud_path).unwrap();
    assert_eq!(cloud.geometry, dem.geometry);
    // |∇terrain| ≤ 0.3·1.3 + 0.2·0.7 + 0.05 < 0.6: within a cell heights differ < 0.6·res·√2/2
    let tolerance = 0.6 * res * std::f64::consts::FRAC_1_SQRT_2;
    let worst = dem
        .data
        .iter()
        .zip(&cloud.data)
        .map(|(a, b)| (f64::from(*a) - f64::from(*b)).abs())
        .fold(0.0, f64::max);
    assert!(worst < tolerance, "worst {worst} ≥ {tolerance}");
    let max = rasterise(&read, res, Reduce::Max, &cloud_path).unwrap();
    assert!(max.data.iter().zip(&cloud.data).all(|(m, c)| m >= c));
}

// --- the map world --------------------------------------------------------------------

const MISSION: &str = r#"
[world.params.mission]
start = { x = 2.0, y = 2.0, yaw = 0.0 }
[[world.params.mission.targets]]
id = "rock"
position = { x = 8.0, y = 5.0 }
pois = [{ x = 7.0, y = 5.0, yaw = 0.0 }]
"#;

fn world_of(dir: &Path, params: &str) -> Result<smug_core::World, String> {
    let text = format!(
        "seed = 1\n[robot]\nlength = 0.5\nwidth = 0.3\n[world]\ntype = \"map\"\n\
         [world.params]\n{params}\n{MISSION}"
    );
    let loaded =
        LoadedConfig::from_text(&text, "test.toml", dir, &[]).map_err(|e| e.to_string())?;
    let pipeline = Pipeline::assemble(&loaded).map_err(|e| e.to_string())?;
    Ok((*pipeline.world.unwrap()).clone())
}

#[test]
fn the_map_world_reads_a_dem_or_a_point_cloud() {
    let dir = scratch("map-world");
    let (res, nx, ny) = (0.5, 24u32, 20u32);
    let values: Vec<f32> = (0..nx * ny).map(|k| (k % 7) as f32 * 0.01).collect();
    let georef = Georef::Tiepoint {
        scale: [res, res],
        at: [0.0, ny as f64 * res],
    };
    write_geotiff(
        &dir.join("dem.tif"),
        [nx, ny],
        Samples::F32(values),
        georef,
        false,
        None,
    );
    let world = world_of(&dir, "dem = \"dem.tif\"").unwrap();
    assert_eq!(world.name, "dem");
    assert_eq!(world.elevation.geometry.size, [24, 20]);
    assert_eq!(world.bounds().max, [12.0, 10.0]);
    assert!(world.traversability.is_none());

    let mut ply = String::from("ply\nformat ascii 1.0\nelement vertex 121\nproperty float x\nproperty float y\nproperty float z\nend_header\n");
    for j in 0..11 {
        for i in 0..11 {
            ply += &format!("{} {} 0.5\n", i as f64 + 0.1, j as f64 + 0.1);
        }
    }
    std::fs::write(dir.join("cloud.ply"), ply).unwrap();
    let world = world_of(
        &dir,
        "point_cloud = \"cloud.ply\"\ncell_size = 0.5\nreduce = \"mean\"",
    )
    .unwrap();
    assert_eq!(world.elevation.geometry.size, [21, 21]);
    assert_eq!(world.elevation.nearest(2.25, 2.25), Some(0.5));
    assert_eq!(world.elevation.nearest(2.75, 2.25), None); // no points: no data

    let err = world_of(&dir, "dem = \"dem.tif\"\npoint_cloud = \"cloud.ply\"").unwrap_err();
    assert!(
        err.contains("give one of `yaml`, `dem` and `point_cloud`"),
        "{err}"
    );
    std::fs::write(dir.join("bad.tif"), "II*\0garbage").unwrap();
    let err = world_of(&dir, "dem = \"bad.tif\"").unwrap_err();
    assert!(err.contains("bad.tif: not a readable TIFF"), "{err}");
}

// --- malformed files: an error, never a panic -------------------------------------------

mod corrupted {
    use super::*;
    use proptest::prelude::*;

    /// Valid files of every reader, written once.
    fn originals() -> &'static [(PathBuf, Vec<u8>)] {
        static FILES: std::sync::OnceLock<Vec<(PathBuf, Vec<u8>)>> = std::sync::OnceLock::new();
        FILES.get_or_init(write_originals)
    }

    fn write_originals() -> Vec<(PathBuf, Vec<u8>)> {
        let dir = scratch("corrupt-originals");
        let mut files = Vec::new();
        let writers: [(&str, Writer); 5] = [
            (
                "a.tif",
                Box::new(|p| {
                    write_geotiff(
                        p,
                        [4, 3],
                        Samples::I16(pixels(|z| z as i16)),
                        TIE,
                        false,
                        Some("-9999"),
                    )
                }),
            ),
            ("a.ply", Box::new(write_ply_ascii)),
            ("le.ply", Box::new(|p| write_ply_binary(p, true))),
            ("a.pcd", Box::new(|p| write_pcd(p, false))),
            ("b.pcd", Box::new(|p| write_pcd(p, true))),
        ];
        for (name, write) in writers {
            let path = dir.join(name);
            write(&path);
            files.push((path.clone(), std::fs::read(&path).unwrap()));
        }
        files
    }

    fn read(path: &Path) -> Result<(), String> {
        if path.extension().is_some_and(|e| e == "tif") {
            read_geotiff(path).map(|_| ()).map_err(|e| e.to_string())
        } else {
            read_point_cloud(path)
                .map(|_| ())
                .map_err(|e| e.to_string())
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]
        /// Flipped bytes and truncations give an error naming the file, or a reading.
        #[test]
        fn readers_survive_corruption(
            which in 0usize..5,
            flips in proptest::collection::vec((any::<prop::sample::Index>(), any::<u8>()), 0..6),
            cut in any::<prop::sample::Index>(),
            truncate in any::<bool>(),
        ) {
            let originals = originals();
            let (path, bytes) = &originals[which];
            let mut bytes = bytes.clone();
            for (at, value) in flips {
                let k = at.index(bytes.len());
                bytes[k] = value;
            }
            if truncate {
                bytes.truncate(cut.index(bytes.len()));
            }
            let target = path.with_file_name(format!(
                "corrupt-{}-{}",
                std::process::id(),
                path.file_name().unwrap().to_string_lossy()
            ));
            std::fs::write(&target, &bytes).unwrap();
            if let Err(err) = read(&target) {
                prop_assert!(err.starts_with(&target.display().to_string()), "{}", err);
            }
        }
    }
}
