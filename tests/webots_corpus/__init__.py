"""The Webots compatibility corpus: its manifest, runner, facts and PROTO census."""
