"""Speed against error: cablefem's settings against MoorDyn's on the flat flume chain."""
