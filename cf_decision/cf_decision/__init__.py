"""cf_decision: the league-independent decision component."""
