"""Reference interpreters (serial and parallel mode): they read the parsed program, never the encoding."""
