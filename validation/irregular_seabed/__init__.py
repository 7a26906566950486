"""desire2023 Sec. 5: a line on an irregular diamond-square seabed, three ways (Figs. 18-20, Table 6)."""
