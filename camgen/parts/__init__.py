"""The part layer shared by camgen and linkgen: drawings with exact arcs, and one writer per format."""
