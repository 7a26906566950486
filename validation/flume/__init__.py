"""desire2023 flume cases (Sec. 4): three seabeds x two fairlead motions."""
