//! The charts of every scene, checked as they would be drawn: no tick, title or legend label
//! in a chart's data area, none over another, in a view showing the chart 200 pixels tall
//! (`flexmodes::record::chart_text_clashes`, the smallest of the explorer's views at
//! 1 280 × 800).

use flexmodes::{
    record::{chart_count, chart_text_clashes},
    scenes::{SceneId, SceneOptions, get},
};

#[test]
fn every_scenes_charts_keep_their_text_off_the_data_and_apart() {
    let (mut charts, mut clashes) = (0, Vec::new());
    for id in SceneId::ALL {
        let out = get(id)
            .execute(&SceneOptions::default())
            .unwrap_or_else(|e| panic!("{}: {e}", id.as_str()));
        charts += chart_count(&out.visuals);
        clashes.extend(
            chart_text_clashes(&out.visuals)
                .into_iter()
                .map(|c| format!("{}: {c}", id.as_str())),
        );
    }
    println!("{charts} charts checked");
    // The modes scene's interface sweep and responses, the failures scene's cost and step
    // charts, the mode sets' responses, the spin-up's Campbell diagrams.
    assert!(charts >= 5, "{charts} charts");
    assert!(clashes.is_empty(), "{}", clashes.join("\n"));
}
