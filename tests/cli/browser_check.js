// Loaded into a copy of the report by tests/cli/report.rs and run in headless Chromium: lists
// every image that did not load, every relative link whose file cannot be read and every
// anchor without its target, in a pre element (id squeal-browser-check) the test reads back.
window.addEventListener('load', () => {
  const out = [];
  const imgs = [...document.images];
  for (const i of imgs) {
    if (!(i.complete && i.naturalWidth > 0)) out.push('BROKEN image ' + i.getAttribute('src'));
  }
  let links = 0;
  for (const a of document.querySelectorAll('a[href]')) {
    const h = a.getAttribute('href');
    if (/^[a-z]+:/i.test(h)) continue;
    links++;
    if (h.startsWith('#')) {
      if (!document.getElementById(decodeURIComponent(h.slice(1)))) out.push('BROKEN anchor ' + h);
      continue;
    }
    try {
      const x = new XMLHttpRequest();
      x.open('GET', new URL(h, document.baseURI).href, false);
      x.send();
    } catch (e) {
      out.push('BROKEN link ' + h);
    }
  }
  // The verdict: from the top of its first paragraph to the bottom of the last one before
  // "Made by", in CSS pixels from the top of the page.
  const ps = [...document.querySelectorAll('main > p')];
  const first = ps.findIndex(x => x.textContent.startsWith('Verdict'));
  const made = ps.findIndex(x => x.textContent.startsWith('Made by'));
  if (first >= 0 && made > first) {
    const top = ps[first].getBoundingClientRect().top + window.scrollY;
    const bottom = ps[made - 1].getBoundingClientRect().bottom + window.scrollY;
    out.push('VERDICT ' + Math.round(top) + ' ' + Math.round(bottom) + ' ' + window.innerWidth);
  } else {
    out.push('BROKEN no verdict above the introduction');
  }
  const p = document.createElement('pre');
  p.id = 'squeal-browser-check';
  p.textContent = 'CHECKED ' + imgs.length + ' images, ' + links + ' links\n' + out.join('\n');
  document.body.appendChild(p);
});
