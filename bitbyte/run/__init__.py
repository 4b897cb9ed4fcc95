"""Run jobs (what a simulator is asked to do), their preparation from a program and a stimulus, the run summary."""
