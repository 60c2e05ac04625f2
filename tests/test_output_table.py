"""A text table (``output._frame``) is the text pandas' ``DataFrame.to_string(index=False)`` gives its text cells,
without importing pandas (0.3 s of a text ``solve``)."""

import string

import pandas as pd
from hypothesis import given, settings
from hypothesis import strategies as st

from clutchopt.output import _frame

CELLS = st.text(alphabet=string.printable + "µΩ°²é\x00\x0b\x0c\x1b\u200b\u3042\U0001F600", max_size=12)
NAMES = st.text(alphabet=string.ascii_letters + string.digits + " .-+/[]()*^_%:,=µΩ°", max_size=10).map(str.strip)
# (clutchopt's column names: no control characters, no space at either end, which pandas strips off a name)


@settings(max_examples=400, deadline=None)
@given(st.lists(NAMES, min_size=1, max_size=5, unique=True).flatmap(
    lambda names: st.lists(st.fixed_dictionaries({}, optional={name: CELLS for name in names}), min_size=1,
                           max_size=6)))
def test_a_table_is_what_pandas_prints_of_its_cells(rows):
    if not any(rows):
        rows = [{"only": ""}]
    assert _frame(rows) == pd.DataFrame(rows).to_string(index=False)  # (a missing cell: NaN, as pandas shows it)


def test_a_table_of_no_rows_says_so():
    assert _frame([]) == "(none)"


def test_columns_are_right_aligned_to_their_widest_cell_or_name():
    assert _frame([{"rank": "1", "coupling": "wedge"}, {"rank": "-", "coupling": "ball", "x": "a\tb"}]).splitlines() \
        == ["rank coupling    x", "   1    wedge  NaN", "   -     ball a\\tb"]  # (a tab shown as pandas shows it)
