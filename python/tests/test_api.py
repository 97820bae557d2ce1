"""Every CLI study keeps its Python call (issue 27): the CLI's commands, read from its own `--help`,
side by side with the package's functions. A new CLI command fails this test until it is given a
Python call here or, with the reason, a place in NO_PYTHON_CALL."""

import re

import loomkin

# The CLI command → the package's function that computes the same thing.
PYTHON_CALL = {
    "law list": loomkin.laws.catalogue,
    "law info": loomkin.laws.info,
    "law sample": loomkin.laws.sample,
    "cycle": loomkin.cycles.report,
    "pick design": loomkin.picking.design,
    "pick simulate": loomkin.picking.simulate,
    "pick sweep": loomkin.picking.sweep,
    "pick montecarlo": loomkin.picking.montecarlo,
    "servo law": loomkin.servo.law,
    "servo torque": loomkin.servo.torque,
    "servo optimize": loomkin.servo.optimize,
    "servo export": loomkin.servo.export,
    "servo check": loomkin.servo.check,
    "shed list": loomkin.shed.presets,
    "shed law": loomkin.shed.law,
    "shed table": loomkin.shed.table,
    "shed pareto": loomkin.shed.pareto,
    "shed best": loomkin.shed.best,
    "shed window": loomkin.shed.window,
    "dobby analyze": loomkin.dobby.analyze,
    "dobby synthesize": loomkin.dobby.synthesize,
    "dobby sweep": loomkin.dobby.sweep,
    "dobby tolerance": loomkin.dobby.tolerance,
    "cam table": loomkin.cams.table,
    "cam profile": loomkin.cams.profile,
    "dyn response": loomkin.dynamics.response,
    "dyn sweep": loomkin.dynamics.sweep,
    "dyn spectrum": loomkin.dynamics.spectrum,
    "dyn compensate": loomkin.dynamics.compensate,
    "dyn optimize": loomkin.dynamics.optimize,
    "dyn two-mass": loomkin.dynamics.two_mass,
    "loom check": loomkin.loom.check,
    "insert budget": loomkin.insertion.budget,
    "insert rapier": loomkin.insertion.rapier,
    "insert projectile": loomkin.insertion.projectile,
    "insert airjet": loomkin.insertion.airjet,
    "loom torque": loomkin.loom.torque,
    "loom stagger": loomkin.loom.stagger,
    "loom servo": loomkin.loom.servo,
    "sley analyze": loomkin.loom.sley,
    "sley synthesize": loomkin.loom.sley_synthesize,
    "drive inertia": loomkin.drive.inertia,
    "drive ripple": loomkin.drive.ripple,
    "drive correct": loomkin.drive.correct,
}

# CLI commands with no Python call, and why.
NO_PYTHON_CALL = {
    # Pictures: the CLI draws PNG/SVG with its own renderer; from Python the same numbers come as
    # tables (the calls above) for matplotlib or any plotting library.
    "law plot": "a picture of law sample's table",
    "pick plot": "a picture of picking.history's table",
    "servo plot": "a picture of servo.torque_curve's table",
    "shed plot": "a picture of shed.table / shed.pareto",
    "dobby plot": "a picture of dobby.analyze / dobby.synthesize",
    "loom timing": "a picture only (the timing diagram); its numbers are loom.check's",
    # Files on disk: joining the CLI's --parts output. Python joins its shards with
    # loomkin.concat and reports Monte-Carlo parts with from_draws (which reads --parts too).
    "merge": "a file tool for --parts; in Python loomkin.concat and from_draws",
    # The local web workbench is a server, not a computation.
    "serve": "the web workbench (a server)",
}


def _commands(cli, *group):
    """The subcommands listed under `Commands:` of `loomkin GROUP --help` (help itself left out)."""
    text = cli(*group, "--help", text=True)
    if "Commands:" not in text:
        return []
    block = text.split("Commands:", 1)[1].split("\n\n", 1)[0]
    return [m.group(1) for m in re.finditer(r"^  ([a-z][a-z0-9-]*)\s", block, re.M) if m.group(1) != "help"]


def test_every_cli_command_has_a_python_call_or_a_reason(cli):
    commands = []
    for top in _commands(cli):
        subs = _commands(cli, top)
        commands += [f"{top} {s}" for s in subs] if subs else [top]
    assert len(commands) > 30, commands
    missing = [c for c in commands if c not in PYTHON_CALL and c not in NO_PYTHON_CALL]
    assert not missing, f"CLI commands with neither a Python call nor a reason: {missing}"
    # Both lists name real commands only (a command renamed or removed is noticed).
    stale = [c for c in list(PYTHON_CALL) + list(NO_PYTHON_CALL) if c not in commands]
    assert not stale, f"not CLI commands: {stale}"
    assert not set(PYTHON_CALL) & set(NO_PYTHON_CALL)


def test_every_python_call_is_public():
    for command, f in PYTHON_CALL.items():
        module = __import__(f.__module__, fromlist=["__all__"])
        assert f.__name__ in getattr(module, "__all__", []), f"{command}: {f.__module__}.{f.__name__}"
