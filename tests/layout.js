// What tests/test_report.py measures of the review page as laid out: in every dimensioned sketch, each label's box
// (getBoundingClientRect) against every other label's and against the parts drawn (the points of the label's box,
// every 2 px, that fall in a part's fill or stroke: exact for rings, bars and rotated shapes, whose own boxes
// are not); and the width of each table and figure against the room it has, and of the page against the window.
(parts) => {
  const STEP = 2;  // px between the points sampled in a label's box
  const INSET = 1;  // px: boxes taken in at their edges, where glyphs and anti-aliased outlines end
  const meet = (a, b, grow = 0) => a.left + INSET < b.right + grow && b.left - grow < a.right - INSET
    && a.top + INSET < b.bottom + grow && b.top - grow < a.bottom - INSET;
  const overlaps = [];
  for (const svg of document.querySelectorAll('svg[aria-label="dimensioned sketch"]')) {
    const labels = [...svg.querySelectorAll("text")].map(t => ({text: t.textContent, box: t.getBoundingClientRect()}));
    labels.forEach((a, i) => labels.slice(i + 1).forEach(b => {
      if (meet(a.box, b.box, -INSET)) overlaps.push([a.text, b.text]);
    }));
    for (const shape of svg.querySelectorAll(parts)) {
      const inverse = shape.getScreenCTM().inverse();
      const reach = shape.getBoundingClientRect();
      for (const {text, box} of labels) {
        if (!meet(box, reach, 10)) continue;  // 10 px: a line's box leaves out its stroke
        let hit = false;
        for (let x = box.left + INSET; x <= box.right - INSET && !hit; x += STEP) {
          for (let y = box.top + INSET; y <= box.bottom - INSET && !hit; y += STEP) {
            const point = new DOMPoint(x, y).matrixTransform(inverse);
            hit = shape.isPointInFill(point) || shape.isPointInStroke(point);
          }
        }
        if (hit) overlaps.push([text, `${shape.tagName}.${shape.getAttribute("class")}`]);
      }
    }
  }
  const fit = (element, name) => ({
    name, width: element.getBoundingClientRect().width, room: element.parentElement.getBoundingClientRect().width,
    scrolls: element.parentElement.scrollWidth > element.parentElement.clientWidth + 1,
  });
  const boxes = [...document.querySelectorAll("table")].map(t => fit(t, t.rows[0].textContent.slice(0, 60)))
    .concat([...document.querySelectorAll("figure > svg")].map(s => fit(s, s.getAttribute("aria-label") || "chart")));
  const page = {width: document.documentElement.scrollWidth, room: document.documentElement.clientWidth};
  return JSON.stringify({overlaps, boxes, page});
}
