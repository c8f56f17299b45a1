//! The one table of the cell types this crate knows and what it can do with each: every
//! per-type cache (shape-function bases, certification tables, the straight-cell shortcut,
//! area rules) is an array indexed by a type's slot here, so adding a type is one line.
//!
//! It owns the table and the lookups; the data cached per type belongs to the modules that
//! build it.

use mesh_model::{CellType, Shape};

use crate::error::JacobianError;

/// What this crate offers for one cell type.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Capabilities {
    /// A certified (Bernstein) sign check of the Jacobian determinant ([`crate::certify_cell`]).
    /// Without it a cell gets the sampled check only ([`crate::sampled_check`]).
    pub certified: bool,
    /// Exact area by quadrature ([`crate::cell_area`]): the 2D types.
    pub area: bool,
    /// The shortcut that certifies a straight-sided high-order cell through its order-1 map.
    pub straight_shortcut: bool,
}

/// Every type with Lagrange shape functions, and whether it has a certificate (all of them
/// now; the column stays for a type that would come with shape functions first). The 14- and
/// 30-node pyramids of Gmsh have rational (Bergot) bases (the `pyramid` module).
const TABLE: [(Shape, u8, bool); 18] = [
    (Shape::Tri, 1, true),
    (Shape::Tri, 2, true),
    (Shape::Tri, 3, true),
    (Shape::Quad, 1, true),
    (Shape::Quad, 2, true),
    (Shape::Quad, 3, true),
    (Shape::Tet, 1, true),
    (Shape::Tet, 2, true),
    (Shape::Prism, 1, true),
    (Shape::Prism, 2, true),
    (Shape::Hex, 1, true),
    (Shape::Hex, 2, true),
    (Shape::Pyramid, 1, true),
    (Shape::Pyramid, 2, true),
    (Shape::Tet, 3, true),
    (Shape::Prism, 3, true),
    (Shape::Hex, 3, true),
    (Shape::Pyramid, 3, true),
];

/// The number of slots: the length of every per-type cache.
pub(crate) const SLOTS: usize = TABLE.len();

/// A feature a caller needs for a type; its name goes into [`JacobianError::Unsupported`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Feature {
    ShapeFunctions,
    Certified,
    Area,
}

impl Feature {
    fn name(self) -> &'static str {
        match self {
            Feature::ShapeFunctions => "the Lagrange shape functions",
            Feature::Certified => "the certified check",
            Feature::Area => "area integration",
        }
    }
}

fn position(ty: CellType) -> Option<usize> {
    TABLE
        .iter()
        .position(|&(s, o, _)| s == ty.shape && o == ty.order)
}

/// What the crate offers for `ty`, or `None` when it has no shape functions for it.
pub fn capabilities(ty: CellType) -> Option<Capabilities> {
    let (_, order, certified) = TABLE[position(ty)?];
    Some(Capabilities {
        certified,
        area: ty.shape.dim() == 2,
        straight_shortcut: certified && order >= 2,
    })
}

/// The cache slot of `ty` when it has `feature`, else [`JacobianError::Unsupported`].
pub(crate) fn slot(ty: CellType, feature: Feature) -> Result<usize, JacobianError> {
    let unsupported = JacobianError::Unsupported {
        ty,
        what: feature.name(),
    };
    let i = position(ty).ok_or(unsupported.clone())?;
    let caps = capabilities(ty).expect("listed type");
    let has = match feature {
        Feature::ShapeFunctions => true,
        Feature::Certified => caps.certified,
        Feature::Area => caps.area,
    };
    if has { Ok(i) } else { Err(unsupported) }
}

/// Every type with shape functions, in table order.
pub fn supported_types() -> impl Iterator<Item = CellType> {
    TABLE.iter().map(|&(s, o, _)| CellType::new(s, o))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_type_with_shape_functions_is_certified() {
        assert!(supported_types().all(|t| capabilities(t).unwrap().certified));
        assert_eq!(supported_types().count(), 18);
        for p in [2, 3] {
            let pyramid = CellType::new(Shape::Pyramid, p);
            assert!(capabilities(pyramid).unwrap().straight_shortcut);
            assert!(slot(pyramid, Feature::Certified).is_ok());
        }
        let p4_tet = CellType::new(Shape::Tet, 4);
        assert!(capabilities(p4_tet).is_none());
        assert!(slot(p4_tet, Feature::ShapeFunctions).is_err());
        let prism = CellType::new(Shape::Prism, 2);
        assert!(slot(prism, Feature::Certified).is_ok());
        assert!(capabilities(prism).unwrap().straight_shortcut);
        assert!(slot(prism, Feature::Area).is_err());
    }
}
