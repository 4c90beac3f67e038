# SPDX-License-Identifier: BSD-3-Clause
"""Shared helpers of the study functions' tests (imcol.laws, imcol.history_compare, imcol.dem_fit): a command's CSV against
an imcol.StudyTable, cell for cell."""
import csv
import math

import numpy as np


def read_csv(path):
    """(header, rows) of a CSV file, its '#' comment lines skipped."""
    with open(path, newline="") as f:
        rows = [row for row in csv.reader(line for line in f if not line.startswith("#"))]
    return rows[0], rows[1:]


def csv_cell(value):
    """A table's value as the command writes it: 12 significant digits, empty for NaN, words with ',' and line
    breaks as ';'."""
    if isinstance(value, (str, np.str_)):
        return str(value).replace(",", ";").replace("\n", ";")
    if math.isnan(value):
        return ""
    return format(float(value), ".12g")


def assert_table_equals_csv(table, header, rows, timings=()):
    """Every column in the CSV's order, every cell but the timing columns' (whose cells need only be there)."""
    assert table.columns == header
    assert len(table) == len(rows)
    for k, name in enumerate(header):
        got = [csv_cell(v) for v in table.table[name]]
        want = [row[k] for row in rows]
        if name in timings:
            assert [g == "" for g in got] == [w == "" for w in want], name
            continue
        assert got == want, name
