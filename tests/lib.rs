//! Workspace-level tests: see the files in this folder.
