// Placeholder translation unit until the command-line driver lands.
