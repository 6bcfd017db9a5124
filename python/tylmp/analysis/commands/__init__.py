"""The subcommands of `tyanalysis` (tylmp.analysis.cli), by what they read: paper_tests (the
paper's tests and its table), further_tests (the tests beyond the paper), records (single records
and files); common (what they share)."""
