"""The reproduction report: the paper's numbers and claims checked against the cubes."""
