// Loaded into a copy of the report by tests/report.rs and run in headless Chromium: lists
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
  const p = document.createElement('pre');
  p.id = 'squeal-browser-check';
  p.textContent = 'CHECKED ' + imgs.length + ' images, ' + links + ' links\n' + out.join('\n');
  document.body.appendChild(p);
});
