//! Writing plan.mcap (whole, or with a replan appended) and reading its plans back.

use super::scene::{scene_messages, PlanScene, Stamped, PLAN_TOPIC};
use super::team::{team_scene_messages, TeamScene};
use crate::ros::cdr::CdrError;
use crate::ros::msgs::{decode, Path};
use crate::ros::schema::{definition, schema_name};
use mcap::records::{MessageHeader, Metadata, Record};
use mcap::{Message, WriteOptions};
use std::collections::{BTreeMap, HashMap};
use std::io::Cursor;
use std::path::{Path as FsPath, PathBuf};

/// The first plan's messages are stamped at this time (1 s), nanoseconds.
const FIRST_PLAN_NS: u64 = 1_000_000_000;
/// A replan's messages start this long after the earlier plan's last one.
const REPLAN_GAP_NS: u64 = 1_000_000_000;

/// Why plan.mcap could not be written or read.
#[derive(Debug, thiserror::Error)]
pub enum McapError {
    /// The file could not be read or written.
    #[error("{}: {what}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// `cannot read` or `cannot write`.
        what: &'static str,
        /// The cause.
        source: std::io::Error,
    },
    /// The MCAP library refused the data.
    #[error("{}: not a readable MCAP file: {source}", path.display())]
    Mcap {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: mcap::McapError,
    },
    /// A message's CDR bytes could not be decoded.
    #[error("{}: message on {topic}: {source}", path.display())]
    Cdr {
        /// The file.
        path: PathBuf,
        /// The message's topic.
        topic: String,
        /// The cause.
        source: CdrError,
    },
}

/// The run a plan came from, for the file's metadata.
pub struct RunInfo {
    /// `plan` or `replan`.
    pub kind: &'static str,
    /// The resolved config as TOML.
    pub config_toml: String,
    /// The seed.
    pub seed: u64,
}

/// Whether a plan replaces the file or follows the plans already in it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WriteMode {
    /// A new file with this plan alone.
    Replace,
    /// The file's plans (if it exists), then this one.
    Append,
}

/// Writes `scene` to `path` as `mode` says, whole or not at all.
pub fn write_plan_mcap(
    path: &FsPath,
    scene: &PlanScene<'_>,
    run: &RunInfo,
    mode: WriteMode,
) -> Result<(), McapError> {
    write_messages(path, run, mode, |t0| scene_messages(scene, t0))
}

/// Writes the team plan of `scene` to `path` as `mode` says, whole or not at all.
pub fn write_team_plan_mcap(
    path: &FsPath,
    scene: &TeamScene<'_>,
    run: &RunInfo,
    mode: WriteMode,
) -> Result<(), McapError> {
    write_messages(path, run, mode, |t0| team_scene_messages(scene, t0))
}

/// Writes the messages `messages` gives for a start time to `path` (after the file's
/// plans for [`WriteMode::Append`]), with `run`'s metadata.
fn write_messages(
    path: &FsPath,
    run: &RunInfo,
    mode: WriteMode,
    messages: impl FnOnce(u64) -> Vec<Stamped>,
) -> Result<(), McapError> {
    let earlier = match mode {
        WriteMode::Append if path.exists() => read_bytes(path)?,
        _ => Vec::new(),
    };
    let mcap_err = |source| McapError::Mcap {
        path: path.to_path_buf(),
        source,
    };
    let options = WriteOptions::new()
        .profile("ros2")
        .library(format!("smug {}", env!("CARGO_PKG_VERSION")))
        .compression(None);
    let mut writer = options.create(Cursor::new(Vec::new())).map_err(mcap_err)?;
    let (t0, plans) = copy_earlier(&mut writer, &earlier).map_err(mcap_err)?;
    write_scene(&mut writer, messages(t0)).map_err(mcap_err)?;
    writer
        .write_metadata(&metadata(run, plans))
        .map_err(mcap_err)?;
    writer.finish().map_err(mcap_err)?;
    let bytes = writer.into_inner().into_inner();
    smug_core::output::write_atomic(path, &bytes).map_err(|source| McapError::Io {
        path: path.to_path_buf(),
        what: "cannot write",
        source,
    })
}

/// The file's bytes.
fn read_bytes(path: &FsPath) -> Result<Vec<u8>, McapError> {
    std::fs::read(path).map_err(|source| McapError::Io {
        path: path.to_path_buf(),
        what: "cannot read",
        source,
    })
}

/// Writes the earlier file's messages and metadata; returns when the next plan starts
/// and how many plans the file held.
fn copy_earlier<W: std::io::Write + std::io::Seek>(
    writer: &mut mcap::Writer<W>,
    earlier: &[u8],
) -> Result<(u64, usize), mcap::McapError> {
    if earlier.is_empty() {
        return Ok((FIRST_PLAN_NS, 0));
    }
    let mut last = 0;
    for message in mcap::MessageStream::new(earlier)? {
        let message = message?;
        last = last.max(message.log_time);
        writer.write(&message)?;
    }
    let mut plans = 0;
    for record in mcap::read::LinearReader::new(earlier)? {
        if let Record::Metadata(m) = record? {
            plans += usize::from(m.name == METADATA_NAME);
            writer.write_metadata(&m)?;
        }
    }
    Ok((last + REPLAN_GAP_NS, plans))
}

/// The name of each plan's metadata record.
const METADATA_NAME: &str = "smug";

/// The metadata of the file's plan number `index` (from 0).
fn metadata(run: &RunInfo, index: usize) -> Metadata {
    let entries = [
        ("kind", run.kind.to_owned()),
        ("plan", index.to_string()),
        ("seed", run.seed.to_string()),
        ("version", env!("CARGO_PKG_VERSION").to_owned()),
        ("config", run.config_toml.clone()),
    ];
    Metadata {
        name: METADATA_NAME.into(),
        metadata: entries.map(|(k, v)| (k.to_owned(), v)).into(),
    }
}

/// Writes `messages`, a channel per topic.
fn write_scene<W: std::io::Write + std::io::Seek>(
    writer: &mut mcap::Writer<W>,
    messages: Vec<Stamped>,
) -> Result<(), mcap::McapError> {
    let mut channels: HashMap<String, u16> = HashMap::new();
    for (sequence, message) in (1u32..).zip(messages) {
        let channel_id = match channels.get(&message.topic) {
            Some(&id) => id,
            None => {
                let schema = writer.add_schema(
                    &schema_name(message.type_name),
                    "ros2msg",
                    definition(message.type_name).as_bytes(),
                )?;
                let id = writer.add_channel(schema, &message.topic, "cdr", &BTreeMap::new())?;
                channels.insert(message.topic.clone(), id);
                id
            }
        };
        let header = MessageHeader {
            channel_id,
            sequence,
            log_time: message.time_ns,
            publish_time: message.time_ns,
        };
        writer.write_to_known_channel(&header, &message.data)?;
    }
    Ok(())
}

/// What a plan.mcap holds, read back.
#[derive(Debug)]
pub struct McapPlan {
    /// The file's profile (`ros2`).
    pub profile: String,
    /// Each plan's path on [`PLAN_TOPIC`] (a team plan's: each robot's, on
    /// `/smug/<robot>/plan`), in order.
    pub paths: Vec<Path>,
    /// Each plan's metadata (`kind`, `plan`, `seed`, `version`, `config`).
    pub metadata: Vec<BTreeMap<String, String>>,
    /// Messages per topic.
    pub counts: BTreeMap<String, usize>,
    /// Each channel's topic, schema name and schema encoding.
    pub channels: Vec<(String, String, String)>,
}

/// Reads the plans of a plan.mcap.
pub fn read_plan_mcap(path: &FsPath) -> Result<McapPlan, McapError> {
    let bytes = read_bytes(path)?;
    let mcap_err = |source| McapError::Mcap {
        path: path.to_path_buf(),
        source,
    };
    let mut read = McapPlan {
        profile: String::new(),
        paths: Vec::new(),
        metadata: Vec::new(),
        counts: BTreeMap::new(),
        channels: Vec::new(),
    };
    for record in mcap::read::LinearReader::new(&bytes).map_err(mcap_err)? {
        match record.map_err(mcap_err)? {
            Record::Header(h) => read.profile = h.profile,
            Record::Metadata(m) if m.name == METADATA_NAME => read.metadata.push(m.metadata),
            _ => {}
        }
    }
    for message in mcap::MessageStream::new(&bytes).map_err(mcap_err)? {
        let message: Message<'_> = message.map_err(mcap_err)?;
        let topic = message.channel.topic.clone();
        note_channel(&mut read.channels, &message);
        *read.counts.entry(topic.clone()).or_default() += 1;
        if is_path_topic(&topic) {
            let decoded = decode::<Path>(&message.data).map_err(|source| McapError::Cdr {
                path: path.to_path_buf(),
                topic,
                source,
            })?;
            read.paths.push(decoded);
        }
    }
    Ok(read)
}

/// Notes a message's channel (topic, schema name, schema encoding) once.
fn note_channel(channels: &mut Vec<(String, String, String)>, message: &Message<'_>) {
    let schema = message.channel.schema.as_deref();
    let entry = (
        message.channel.topic.clone(),
        schema.map_or(String::new(), |s| s.name.clone()),
        schema.map_or(String::new(), |s| s.encoding.clone()),
    );
    if !channels.contains(&entry) {
        channels.push(entry);
    }
}

/// Whether `topic` carries a plan's path: [`PLAN_TOPIC`], or a team robot's
/// `/smug/<robot>/plan`.
fn is_path_topic(topic: &str) -> bool {
    topic == PLAN_TOPIC
        || topic
            .strip_prefix("/smug/")
            .and_then(|rest| rest.strip_suffix("/plan"))
            .is_some_and(|robot| !robot.is_empty() && !robot.contains('/'))
}
