"""tylmp.analysis: figures and tables for the Thornton periodic-cell tests (CSV records of fix
cell/servo), behind the `tyanalysis` command.

Modules: io (readers and writers), invariants (p, q, b, sin phi, Lode angle, eta, Pi plane,
failure surfaces), metrics (derived histories, key numbers), figures (PNG, Agg), paper (the
paper's numbers), compare (against the paper, markdown tables), programmes (the run lists of
`tyanalysis reproduce`), reproduce (runs them), fidelity (the trace study's table),
micromechanics, cyclic, liggghts, cli (the `tyanalysis <subcommand>` command; also
`python -m tylmp.analysis`) and commands (its subcommands).
"""
__all__ = ["io", "invariants", "metrics", "figures", "paper", "compare", "programmes",
           "reproduce", "fidelity", "micromechanics", "cyclic", "liggghts", "cli", "commands"]
