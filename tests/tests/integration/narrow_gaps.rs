//! The reproductions of the robustness review (defects D1, D2 and Q): bodies in narrow gaps,
//! a thin first layer under coarse wall edges, cells so thin that a non-exact orientation test
//! rounds their area to zero. Each must give a mesh that passes every check at P1 and P3.

use crate::checked_run;

use checked_run::{Verdict, run_and_check};

/// Meshes `toml` at P1 and P3 and checks each result, with no triangle of `angle_bound`
/// degrees or more.
fn assert_meshes(toml: &str, angle_bound: f64) {
    let dir = tempfile::tempdir().unwrap();
    let case = dir.path().join("case.toml");
    std::fs::write(&case, toml).unwrap();
    for order in [1, 3] {
        match run_and_check(dir.path(), &case, order, angle_bound) {
            Ok(Verdict::Valid(_)) => {}
            Ok(Verdict::Refused(msg)) => panic!("P{order} refused: {msg}\n{toml}"),
            Err(why) => panic!("P{order}: {why}\n{toml}"),
        }
    }
}

fn two_circles(gap: f64) -> String {
    format!(
        "name = \"two-circles\"\n\
         [[loop]]\nrole = \"wall\"\ncircle = {{ center = [0.0, 0.0], radius = 0.5 }}\n\
         [[loop]]\nrole = \"wall\"\ncircle = {{ center = [{}, 0.0], radius = 0.5 }}\n\
         [[loop]]\nrole = \"farfield\"\ncircle = {{ center = [0.5, 0.0], radius = 20.0 }}\n",
        1.0 + gap
    )
}

/// D1 and Q: two circles close together gave inverted P3 cells (gaps 0.01–0.05) and
/// triangles up to 170° (gap 1e-5): their wall edges were many times longer than the gap.
/// (At gap 0.05 the fill where the fronts meet above and below the gap still has a 144°
/// triangle: the bound here is the hard one, 150°.)
#[test]
fn two_circles_at_every_gap_give_valid_well_shaped_meshes() {
    for gap in [1e-5, 1e-3, 0.01, 0.03, 0.05, 0.1] {
        assert_meshes(&two_circles(gap), 150.0);
    }
}

/// D1: a thin stack of layers (first height 2.2e-7, growth 1.1, 60 layers: 6.7e-4 in all)
/// under wall edges whose bulge (2.6e-3) is larger than the whole stack.
#[test]
fn thin_layer_stack_under_a_coarse_blob() {
    let toml = "name = \"blob\"\n\
        [[loop]]\nrole = \"wall\"\n\
        points = [[0.478,0.123],[0.268,0.422],[0.031,0.491],[-0.425,0.309],[-0.489,0.194],\
        [-0.478,-0.189],[-0.326,-0.395],[-0.087,-0.455],[0.376,-0.353],[0.479,-0.263],[0.539,-0.138]]\n\
        [[loop]]\nrole = \"farfield\"\ncircle = { center = [0.0, 0.0], radius = 20.0 }\n\
        [boundary]\ngrowth = 1.19\n\
        [layers]\nfirst_height = 2.2e-7\ngrowth = 1.1\n";
    assert_meshes(toml, 135.0);
}

/// D2: a first height of 1e-9 at a concave corner; cells so thin that the shoelace sum on
/// absolute coordinates rounded their area to 0 and the mesh was called invalid.
#[test]
fn l_shape_with_a_first_height_of_1e_9() {
    let toml = "name = \"lshape-thin\"\n\
        [[loop]]\nrole = \"wall\"\npoints = [[0,0],[1,0],[1,0.3],[0.3,0.3],[0.3,1],[0,1]]\n\
        [[loop]]\nrole = \"farfield\"\ncircle = { center = [0.5, 0.5], radius = 15.0 }\n\
        [layers]\nfirst_height = 1e-9\n";
    assert_meshes(toml, 135.0);
}

/// D2 and Q: two unit squares 1e-8 and 1e-7 apart (were "signed area 0" and a 175° triangle).
#[test]
fn two_squares_almost_touching() {
    for gap in [1e-8, 1e-7] {
        let toml = format!(
            "name = \"two-squares\"\n\
             [[loop]]\nrole = \"wall\"\npoints = [[0,0],[1,0],[1,1],[0,1]]\n\
             [[loop]]\nrole = \"wall\"\npoints = [[{a},0],[{b},0],[{b},1],[{a},1]]\n\
             [[loop]]\nrole = \"farfield\"\ncircle = {{ center = [1.0, 0.5], radius = 20.0 }}\n",
            a = 1.0 + gap,
            b = 2.0 + gap
        );
        assert_meshes(&toml, 135.0);
    }
}
