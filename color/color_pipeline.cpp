// Placeholder translation unit until the colour pipeline lands.
