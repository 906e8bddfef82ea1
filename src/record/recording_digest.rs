//! What a recording holds, without the ids that differ from one run to the next: for telling
//! whether two recordings (one reached by a sequence of switches in the explorer, one made
//! fresh) show the same thing.

use std::collections::BTreeMap;

use super::rerun_sdk::external::re_log_types::LogMsg;

/// Arrow metadata: a column's or a chunk's entity path, and a column's kind (`control`
/// for the row ids).
pub(super) const ENTITY_PATH: &str = "rerun:entity_path";
const KIND: &str = "rerun:kind";

/// A recording's content, entity by entity: for each entity the text of each chunk's data
/// columns (component values and times), sorted. Store ids, chunk ids and row ids are left
/// out (the blueprint's view and container ids are the same in every run: they follow from
/// the layout).
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct RecordingDigest {
    /// The recording's entities.
    pub recording: BTreeMap<String, Vec<String>>,
    /// The blueprint's entities.
    pub blueprint: BTreeMap<String, Vec<String>>,
}

impl RecordingDigest {
    /// The digest of `messages` (a recording and its blueprint, as
    /// [`super::Recorder::messages`] gives them).
    pub fn of(messages: &[LogMsg]) -> Self {
        let mut out = Self::default();
        for m in messages {
            let LogMsg::ArrowMsg(store, msg) = m else {
                continue;
            };
            let batch = &msg.batch;
            let schema = batch.schema();
            let Some(entity) = schema.metadata().get(ENTITY_PATH) else {
                continue;
            };
            let mut columns = Vec::new();
            for (field, column) in schema.fields().iter().zip(batch.columns()) {
                if field.metadata().get(KIND).map(String::as_str) == Some("control") {
                    continue;
                }
                columns.push(format!("{}: {column:?}", field.name()));
            }
            let chunk = columns.join("\n");
            let side = if store.is_blueprint() {
                &mut out.blueprint
            } else {
                &mut out.recording
            };
            side.entry(entity.clone()).or_default().push(chunk);
        }
        for chunks in out.recording.values_mut().chain(out.blueprint.values_mut()) {
            chunks.sort();
        }
        out
    }

    /// The recording's entity paths.
    pub fn entities(&self) -> Vec<&str> {
        self.recording.keys().map(String::as_str).collect()
    }

    /// The first difference from `other`, described (`None` when equal); entities in
    /// `presence_only` must exist in both but may differ in content (wall times).
    pub fn difference(&self, other: &Self, presence_only: &[&str]) -> Option<String> {
        for (side, a, b) in [
            ("recording", &self.recording, &other.recording),
            ("blueprint", &self.blueprint, &other.blueprint),
        ] {
            let only_a: Vec<&String> = a.keys().filter(|k| !b.contains_key(*k)).collect();
            let only_b: Vec<&String> = b.keys().filter(|k| !a.contains_key(*k)).collect();
            if !only_a.is_empty() || !only_b.is_empty() {
                return Some(format!(
                    "{side} entities differ: only in the first {only_a:?}, only in the second \
                     {only_b:?}"
                ));
            }
            for (k, chunks) in a {
                if presence_only.contains(&k.as_str()) {
                    continue;
                }
                if b.get(k) != Some(chunks) {
                    let first = chunks.concat();
                    let second = b.get(k).map(|c| c.concat()).unwrap_or_default();
                    let at = first
                        .chars()
                        .zip(second.chars())
                        .take_while(|(x, y)| x == y)
                        .count();
                    let show = |s: &str| {
                        s.chars()
                            .skip(at.saturating_sub(40))
                            .take(160)
                            .collect::<String>()
                    };
                    return Some(format!(
                        "{side} entity {k} differs at character {at}: {:?} against {:?}",
                        show(&first),
                        show(&second)
                    ));
                }
            }
        }
        None
    }
}
