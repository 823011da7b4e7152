//! The spinner `smug plan`, `smug replan` and team plans show on a terminal: the
//! running stage and the legs planned so far.

/// A spinner on stderr naming the running stage, shown only in a terminal.
pub(crate) struct Progress(Option<indicatif::ProgressBar>);

impl Progress {
    pub(crate) fn start(stage: &str) -> Self {
        use std::io::IsTerminal;
        if !std::io::stderr().is_terminal() {
            return Self(None);
        }
        let bar = indicatif::ProgressBar::new_spinner();
        if let Ok(style) = indicatif::ProgressStyle::with_template("{spinner} {msg} {prefix}") {
            bar.set_style(style);
        }
        bar.enable_steady_tick(std::time::Duration::from_millis(100));
        bar.set_message(stage.to_string());
        Self(Some(bar))
    }

    pub(crate) fn stage(&self, stage: &str) {
        if let Some(bar) = &self.0 {
            bar.set_message(stage.to_string());
        }
    }

    /// Shows beside the message the run's mission stage and its legs planned of those
    /// asked so far ("planning: selection, 40/63 legs planned"), read at every tick.
    pub(crate) fn follow(&self, run: &smug_core::RunProgress) {
        let Some(bar) = &self.0 else {
            return;
        };
        let run = run.clone();
        let legs = move |_: &indicatif::ProgressState, w: &mut dyn std::fmt::Write| {
            let stage = run.stage();
            if !stage.is_empty() {
                let _ = write!(w, ": {stage}");
            }
            let (answered, asked) = run.legs();
            if asked > 0 {
                let _ = write!(w, ", {answered}/{asked} legs planned");
            }
        };
        if let Ok(style) = indicatif::ProgressStyle::with_template("{spinner} {msg}{legs}") {
            bar.set_style(style.with_key("legs", legs));
        }
    }

    /// Shows beside the message each robot's legs planned of those asked so far
    /// ("anymal 40/63, rover 3/5 legs planned"), read at every tick.
    pub(crate) fn follow_team(&self, robots: Vec<(String, smug_core::RunProgress)>) {
        let Some(bar) = &self.0 else {
            return;
        };
        let legs = move |_: &indicatif::ProgressState, w: &mut dyn std::fmt::Write| {
            let parts: Vec<String> = robots
                .iter()
                .map(|(name, run)| {
                    let (answered, asked) = run.legs();
                    format!("{name} {answered}/{asked}")
                })
                .collect();
            let _ = write!(w, ": {} legs planned", parts.join(", "));
        };
        if let Ok(style) = indicatif::ProgressStyle::with_template("{spinner} {msg}{legs}") {
            bar.set_style(style.with_key("legs", legs));
        }
    }

    pub(crate) fn finish(&self) {
        if let Some(bar) = &self.0 {
            bar.finish_and_clear();
        }
    }
}
