"""Input and output: measurement readers (CSV, pedestrian format, gzip, stdin), the fast number
formatter, atomic files and folders, local metric frames for lat/lon, time units, and the real datasets.
Imports nothing of lgekf but itself."""
