//! The `loomkin` binary run as a user runs it: one test binary, a module per topic.

mod cam;
mod common;
mod contracts;
mod dobby;
mod docs;
mod drive;
mod dynamics;
mod ends;
mod insert;
mod insert_air;
mod law;
mod limits;
mod loom;
mod messages;
mod output;
mod parts;
mod pick;
mod plots;
mod scripts;
mod serve;
mod servo;
mod shard;
mod shed;
mod sley;
mod snapshots;
mod units;
