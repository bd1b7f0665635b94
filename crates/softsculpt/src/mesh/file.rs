//! Reading a mesh file of any format into a [`LoadedMesh`] (one weld, check, orientation and
//! piece count for all: [`prepare`]) and writing a simulated shape back in any of them; which
//! format is which, and what each keeps, is in [`format`](super::format). Bytes in, bytes out: the
//! caller reads files.

use super::format::{fan_triangles, y_up_to_z_up, z_up_to_y_up, MeshFormat, UpAxis, WriteOptions, READ_EXTENSIONS, WRITE_EXTENSIONS};
use super::loaded::{prepare, LoadedMesh};
use super::obj::{self, ObjData};
use super::{gltf, ply, stl};
use crate::error::MeshError;

/// Read mesh bytes of the given format (or, without one, the format [`MeshFormat::sniff`]
/// finds) and prepare them: weld, drop degenerate faces, orient, count pieces.
pub fn load(bytes: &[u8], format: Option<MeshFormat>) -> Result<LoadedMesh, MeshError> {
    let format = match format.or_else(|| MeshFormat::sniff(bytes)) {
        Some(f) => f,
        None => {
            return Err(MeshError::Invalid(format!(
                "cannot tell the file's format: it is none of {READ_EXTENSIONS} by its first bytes"
            )))
        }
    };
    let data = match format {
        MeshFormat::Obj => obj::parse(bytes)?,
        MeshFormat::Ply => ply::parse(bytes)?,
        MeshFormat::Stl => stl::parse(bytes)?,
        MeshFormat::Gltf | MeshFormat::Glb => gltf::parse(bytes, format)?,
    };
    check_finite(&data, format)?;
    let mut loaded = prepare(data)?;
    loaded.report.format = Some(format);
    if matches!(format, MeshFormat::Gltf | MeshFormat::Glb) {
        loaded.report.up_axis = UpAxis::Y;
    }
    Ok(loaded)
}

fn check_finite(data: &ObjData, format: MeshFormat) -> Result<(), MeshError> {
    if let Some(i) = data.positions.iter().position(|x| !x.is_finite()) {
        return Err(MeshError::Format {
            format: format.name(),
            message: format!("vertex {} has a coordinate that is not finite (NaN or infinity)", i / 3 + 1),
        });
    }
    Ok(())
}

impl LoadedMesh {
    /// Declare the file's up axis. `Z` rotates the mesh (and its source) to Y-up; `Y` keeps it.
    /// Returns a warning when this contradicts what the format says (glTF is Y-up).
    pub fn set_up_axis(&mut self, up: UpAxis) -> Option<String> {
        let gltf = matches!(self.report.format, Some(MeshFormat::Gltf | MeshFormat::Glb));
        if up == UpAxis::Z {
            z_up_to_y_up(&mut self.mesh.positions);
            z_up_to_y_up(&mut self.source.positions);
        }
        self.report.up_axis = up;
        self.report.up_rotated = up == UpAxis::Z;
        (gltf && up == UpAxis::Z)
            .then(|| "glTF files are Y-up by specification; rotated from Z-up anyway, as asked".to_string())
    }

    /// The source's positions with every used vertex replaced by its simulated position.
    fn source_positions(&self, positions: &[f64]) -> Vec<f64> {
        let mut out = self.source.positions.clone();
        for (s, &m) in self.source_to_mesh.iter().enumerate() {
            if m != u32::MAX {
                out[3 * s..3 * s + 3].copy_from_slice(&positions[3 * m as usize..3 * m as usize + 3]);
            }
        }
        out
    }

    /// The shape `positions` (the simulated vertices, flat `xyz…`) as a file of `format`, in the
    /// source's vertex order and polygons (triangulated as fans where the format needs
    /// triangles). glTF text is not written: use GLB.
    pub fn write(&self, format: MeshFormat, positions: &[f64], header: &str) -> Result<Vec<u8>, MeshError> {
        self.write_with(format, positions, header, WriteOptions::default())
    }

    /// [`LoadedMesh::write`] with `options`: the frame (Z turns the Y-up positions to Z-up,
    /// [`y_up_to_z_up`], the inverse of what reading with `Z` did, so a file read Z-up is written
    /// back Z-up) and whether OBJ and PLY get the source's polygons or triangles (fans).
    pub fn write_with(&self, format: MeshFormat, positions: &[f64], header: &str, options: WriteOptions) -> Result<Vec<u8>, MeshError> {
        let mut out = self.source_positions(positions);
        if options.up == UpAxis::Z {
            y_up_to_z_up(&mut out);
        }
        let fans;
        let polygons = if options.triangulate {
            let tris = fan_triangles(&self.source);
            fans = ObjData { positions: Vec::new(), arities: vec![3; tris.len()], indices: tris.into_iter().flatten().collect() };
            &fans
        } else {
            &self.source
        };
        Ok(match format {
            MeshFormat::Obj => obj::write(&out, polygons, header),
            MeshFormat::Ply => ply::write(&out, polygons, header),
            MeshFormat::Stl => stl::write(&out, &self.source, header),
            MeshFormat::Glb => gltf::write_glb(&out, &self.source, header),
            MeshFormat::Gltf => {
                return Err(MeshError::Invalid(format!("cannot write .gltf text; write {WRITE_EXTENSIONS}")));
            }
        })
    }

    /// OBJ text in the source's vertex order and polygons, with positions taken from `positions`
    /// (the simulated vertices, flat `xyz…`). Unused source vertices keep their position.
    pub fn write_obj(&self, positions: &[f64], header: &str) -> Vec<u8> {
        obj::write(&self.source_positions(positions), &self.source, header)
    }
}
