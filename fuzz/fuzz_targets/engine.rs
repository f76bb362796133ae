//! Structured DH tables straight into `validate` and the engine: no panic, and the
//! engine's model equals the numeric reference.
#![no_main]

use kinegen_core::model::validate::validate;
use kinegen_core::Options;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|table: kinegen_fuzz::table::Table| {
    let raw = table.raw();
    let Ok(robot) = validate(&raw) else {
        return; // invalid tables are the TOML target's business
    };
    // A smaller budget than the default keeps an input under a second in the worst cases
    // (7 joints, everything named); the fallback paths it takes are the ones under test.
    let mut options = Options::default();
    options.budget.nodes = 1_000;
    kinegen_fuzz::check::robot_outcome(&robot, &options, &table.q());
});
