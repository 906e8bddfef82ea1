//! Bad input gives a named error with its cause, never a panic.

use flexmodes::reduction::ReductionError;
use flexmodes::{
    error::CoreError as Error,
    fem::{BeamParameters, SlabParameters, beam, slab},
    reduction::{
        EitelbergParameters, Method, ModeSelection, NodalFixedAxes, ReductionRequest, eitelberg,
        reduce,
    },
    scenes::{self, SceneOptions},
};

#[test]
fn unknown_scene() {
    let e = scenes::find("beam-mode").err().unwrap();
    assert!(matches!(e, flexmodes::Error::UnknownScene { ref id, .. } if id == "beam-mode"));
    assert!(
        e.to_string().contains("beam-modes"),
        "lists the known scenes: {e}"
    );
}

#[test]
fn node_out_of_range_and_duplicates() {
    let model = beam(&BeamParameters::default());
    let e = reduce(
        &model,
        &ReductionRequest::of(Method::Guyan).boundary(&[1, 6]),
    )
    .unwrap_err();
    assert!(
        matches!(
            e,
            Error::NodeOutOfRange {
                node: 6,
                count: 5,
                ..
            }
        ),
        "{e}"
    );
    let e = reduce(&model, &ReductionRequest::of(Method::Guyan).boundary(&[0])).unwrap_err();
    assert!(matches!(e, Error::NodeOutOfRange { node: 0, .. }), "{e}");
    let e = reduce(
        &model,
        &ReductionRequest::of(Method::Guyan).boundary(&[1, 1]),
    )
    .unwrap_err();
    assert!(matches!(e, Error::DuplicateNode { node: 1 }), "{e}");
    let all: Vec<usize> = (1..=5).collect();
    assert!(matches!(
        reduce(&model, &ReductionRequest::of(Method::Guyan).boundary(&all)).unwrap_err(),
        Error::Reduction(ReductionError::NoInterior { .. })
    ));
    assert!(matches!(
        reduce(&model, &ReductionRequest::of(Method::Guyan).boundary(&[])).unwrap_err(),
        Error::Reduction(ReductionError::NoBoundary)
    ));
}

#[test]
fn singular_interior_for_too_few_boundary_dofs() {
    let model = slab(&SlabParameters::default());
    for method in [
        Method::Guyan,
        Method::CraigBampton,
        Method::ModeCondensation,
    ] {
        let p = ReductionRequest {
            boundary_nodes: vec![16],
            modes: ModeSelection::Count(4),
            ..Default::default()
        };
        match reduce(&model, &p.with_method(method)).unwrap_err() {
            Error::Reduction(ReductionError::SingularInterior {
                boundary_nodes,
                rank_deficiency,
                ..
            }) => {
                assert_eq!(boundary_nodes, vec![16]);
                assert_eq!(
                    rank_deficiency, 3,
                    "{method:?}: three rotations about node 16"
                );
            }
            e => panic!("{method:?}: {e}"),
        }
    }
    // Two nodes leave the rotation about the line through them free.
    let e = reduce(
        &model,
        &ReductionRequest::of(Method::CraigBampton)
            .boundary(&[16, 30])
            .modes(ModeSelection::Count(2)),
    )
    .unwrap_err();
    assert!(
        matches!(
            e,
            Error::Reduction(ReductionError::SingularInterior {
                rank_deficiency: 1,
                ..
            })
        ),
        "{e}"
    );
    // Modal truncation does not need K_ii invertible.
    assert!(
        reduce(
            &model,
            &ReductionRequest {
                method: Method::ModalTruncation,
                boundary_nodes: vec![16],
                modes: ModeSelection::Count(4),
                ..Default::default()
            }
        )
        .is_ok()
    );
}

#[test]
fn too_many_modes() {
    let model = beam(&BeamParameters::default());
    let e = reduce(
        &model,
        &ReductionRequest::of(Method::ModeCondensation)
            .boundary(&[1, 5])
            .modes(ModeSelection::Count(7)),
    )
    .unwrap_err();
    assert!(
        matches!(
            e,
            Error::Reduction(ReductionError::TooManyModes {
                requested: 7,
                available: 6
            })
        ),
        "{e}"
    );
    let e = reduce(
        &model,
        &ReductionRequest::of(Method::CraigBampton)
            .boundary(&[1, 5])
            .modes(ModeSelection::UpToHz(f64::NAN)),
    )
    .unwrap_err();
    assert!(
        matches!(
            e,
            Error::Reduction(ReductionError::InvalidCutoff { hz }) if hz.is_nan()
        ),
        "{e}"
    );
}

#[test]
fn eitelberg_refuses_an_unstable_a() {
    let model = beam(&BeamParameters::default());
    let e = eitelberg(
        &model,
        &[1, 3, 5],
        &EitelbergParameters {
            output_feedback: false,
        },
    )
    .unwrap_err();
    match e {
        Error::Reduction(ReductionError::UnstableSystem { max_real_part }) => {
            assert!(max_real_part.abs() < 1e-6)
        }
        e => panic!("{e}"),
    }
}

#[test]
fn nodal_fixed_anchor_must_be_a_boundary_column() {
    let model = slab(&SlabParameters::default());
    // Node 28 anchors the ξ axis but is not a boundary node here.
    let cb = reduce(
        &model,
        &ReductionRequest::of(Method::CraigBampton)
            .boundary(&[16, 18, 30])
            .modes(ModeSelection::Count(2)),
    )
    .unwrap();
    let e = NodalFixedAxes::slab_default()
        .apply(&model, &cb)
        .unwrap_err();
    assert!(
        matches!(
            e,
            Error::Reduction(ReductionError::AnchorNotInBasis { node: 28, .. })
        ),
        "{e}"
    );
}

#[test]
fn scene_options_are_checked() {
    let bad_axes = SceneOptions {
        axes: Some(flexmodes::dynamics::AxisKind::Mean),
        ..Default::default()
    };
    let e = scenes::find("beam-modes")
        .unwrap()
        .execute(&bad_axes)
        .unwrap_err();
    assert!(matches!(e, flexmodes::Error::UnknownAxes { .. }), "{e}");
    let bad_method = SceneOptions {
        methods: Some(vec![Method::Eitelberg]),
        ..Default::default()
    };
    let e = (scenes::find("beam-profiles").unwrap().run)(&bad_method).unwrap_err();
    assert!(matches!(e, flexmodes::Error::UnknownMethod { .. }), "{e}");
    let singular = SceneOptions {
        boundary: Some(vec![16]),
        ..Default::default()
    };
    let e = (scenes::find("slab-modes").unwrap().run)(&singular).unwrap_err();
    assert!(
        matches!(
            e,
            flexmodes::Error::Core(Error::Reduction(ReductionError::SingularInterior { .. }))
        ),
        "{e}"
    );
}
