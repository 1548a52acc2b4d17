"""One thin module per subcommand: load spec -> call core -> hand to report."""
