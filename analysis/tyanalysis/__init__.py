"""tyanalysis: figures and tables for the Thornton periodic-cell tests (CSV of fix cell/servo).

Modules: io (readers), invariants (p, q, b, sin phi, Lode angle, eta, Pi plane, failure
surfaces), metrics (derived histories, key numbers), figures (PNG, Agg), compare (paper values,
markdown table), cli (the `tyanalysis <subcommand>` command).
"""
__all__ = ["io", "invariants", "metrics", "figures", "compare", "cli"]
