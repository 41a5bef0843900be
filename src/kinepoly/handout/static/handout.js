(function () {
  "use strict";
  var pages = Array.prototype.slice.call(document.querySelectorAll("section.page"));
  var slider = document.getElementById("slider");
  var previous = document.getElementById("previous");
  var next = document.getElementById("next");
  var where = document.getElementById("where");
  var current = 0;
  var drawing = document.querySelector("section.page svg");
  var caption = drawing.querySelector("title");
  var parts = Array.prototype.slice.call(drawing.querySelectorAll("g[data-pages]")).map(function (group) {
    return [group, group.getAttribute("data-pages").split(" ").map(function (range) {
      var ends = range.split("-");
      return [parseInt(ends[0], 10), parseInt(ends[ends.length - 1], 10)];
    })];
  });
  function draw(number) {
    parts.forEach(function (part) {
      var shown = part[1].some(function (range) { return range[0] <= number && number <= range[1]; });
      if (shown) { part[0].removeAttribute("display"); } else { part[0].setAttribute("display", "none"); }
    });
    caption.textContent = pages[number - 1].getAttribute("data-title");
    pages[number - 1].querySelector(".drawing").appendChild(drawing);
  }
  function show(k) {
    k = Math.max(0, Math.min(pages.length - 1, k));
    draw(k + 1);
    pages.forEach(function (page, n) { page.hidden = n !== k; });
    current = k;
    slider.value = String(k + 1);
    previous.disabled = k === 0;
    next.disabled = k === pages.length - 1;
    where.textContent = pages[k].getAttribute("data-label");
    document.body.setAttribute("data-page", String(k + 1));
    var hash = "#page-" + (k + 1);
    if (location.hash !== hash) {
      try { history.replaceState(null, "", hash); } catch (error) { /* an address that cannot change */ }
    }
  }
  function fromHash() {
    var m = /^#page-(\d+)$/.exec(location.hash);
    return m ? parseInt(m[1], 10) - 1 : 0;
  }
  previous.addEventListener("click", function () { show(current - 1); });
  next.addEventListener("click", function () { show(current + 1); });
  slider.addEventListener("input", function () { show(parseInt(slider.value, 10) - 1); });
  document.addEventListener("keydown", function (event) {
    if (event.target === slider || event.altKey || event.ctrlKey || event.metaKey) { return; }
    if (event.key === "ArrowRight" || event.key === "PageDown") { show(current + 1); }
    else if (event.key === "ArrowLeft" || event.key === "PageUp") { show(current - 1); }
    else if (event.key === "Home") { show(0); }
    else if (event.key === "End") { show(pages.length - 1); }
    else { return; }
    event.preventDefault();
  });
  window.addEventListener("hashchange", function () { show(fromHash()); });
  show(fromHash());
}());
