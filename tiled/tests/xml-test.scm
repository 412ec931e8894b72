;;; Tests for (downstroke xml): expat-backed parsing into SXML-shaped trees.
(import (downstroke test) (downstroke xml)
        scheme (chicken base) (chicken condition) (chicken string)
        (chicken file) (chicken io) (chicken random))

;; An error whose message contains text.
(define (xml-error-mentions text)
  (lambda (exn) (and (xml-error? exn) (substring-index text (error-text exn)) #t)))

;; An xml-error whose message is exactly text.
(define (xml-error-is text)
  (lambda (exn) (and (xml-error? exn) (string=? text (error-text exn)))))

;; 'ok when str parses, 'error when it raises an xml-error; anything else
;; (another kind of error) is returned as is so a test shows it.
(define (xml-outcome str)
  (call/cc
   (lambda (k)
     (with-exception-handler
      (lambda (exn) (k (if (xml-error? exn) 'error (error-text exn))))
      (lambda () (and (pair? (xml-parse-string str)) 'ok))))))

(define (xml-count-errors outcomes)
  (let loop ((xs outcomes) (n 0))
    (cond ((null? xs) n)
          ((eq? (car xs) 'error) (loop (cdr xs) (+ n 1)))
          (else (loop (cdr xs) n)))))

(define (xml-iota n)
  (let loop ((i (- n 1)) (acc '()))
    (if (< i 0) acc (loop (- i 1) (cons i acc)))))

(define (xml-write-file path text)
  (with-output-to-file path (lambda () (write-string text))))

(define (xml-repeat-string s n)
  (let loop ((n n) (acc '()))
    (if (zero? n) (string-intersperse acc "") (loop (- n 1) (cons s acc)))))

(define xml-small-doc
  "<?xml version=\"1.0\" encoding=\"UTF-8\"?>
<map version=\"1.10\" width=\"2\" height=\"2\">
 <!-- a comment -->
 <layer id=\"1\" name=\"a\">
  <data encoding=\"csv\">1,2
3,4</data>
 </layer>
 <objectgroup name=\"o\"><object id=\"7\" x=\"1.5\"/></objectgroup>
</map>
")

(test-group "xml: trees"
  (test "small document, exact tree"
        '(*TOP*
          (map (@ (version "1.10") (width "2") (height "2"))
               "\n \n "
               (layer (@ (id "1") (name "a"))
                      "\n  "
                      (data (@ (encoding "csv")) "1,2\n3,4")
                      "\n ")
               "\n "
               (objectgroup (@ (name "o")) (object (@ (id "7") (x "1.5"))))
               "\n"))
        ;; The comment is dropped and the text on both sides of it merges.
        (xml-parse-string xml-small-doc))
  (test "element without attributes has no (@)" '(*TOP* (a (b) "t"))
        (xml-parse-string "<a><b/>t</a>"))
  (test "empty root" '(*TOP* (root)) (xml-parse-string "<root/>"))
  (test "attributes in document order"
        '(*TOP* (e (@ (z "1") (a "2") (m "3") (b "4"))))
        (xml-parse-string "<e z='1' a=\"2\" m='3' b='4'/>"))
  (test "names verbatim, no namespace processing"
        '(*TOP* (t:map (@ (xmlns:t "urn:x") (xml:space "preserve") (t:k "v")) (t:x)))
        (xml-parse-string "<t:map xmlns:t='urn:x' xml:space='preserve' t:k='v'><t:x/></t:map>"))
  (test "nesting"
        '(*TOP* (a (b (c (d "deep"))) (e)))
        (xml-parse-string "<a><b><c><d>deep</d></c></b><e></e></a>"))
  (test "text, CDATA and references merge into one string"
        '(*TOP* (t "a<b>&c&AA\"'<>z"))
        (xml-parse-string "<t>a<![CDATA[<b>]]>&amp;c&#x26;&#x41;&#65;&quot;&apos;&lt;&gt;z</t>"))
  (test "references in attribute values"
        '(*TOP* (t (@ (v "x&y<A\"'"))))
        (xml-parse-string "<t v='x&amp;y&lt;&#x41;&quot;&apos;'/>"))
  (test "attribute value whitespace normalised as XML requires"
        '(*TOP* (t (@ (v "a b  c"))))
        (xml-parse-string "<t v='a\tb\n c'/>"))
  (test "whitespace-only text kept" '(*TOP* (a "  \n\t " (b) " "))
        (xml-parse-string "<a>  \n\t <b/> </a>"))
  (test "CRLF becomes LF" '(*TOP* (a "x\ny\nz"))
        (xml-parse-string "<a>x\r\ny\rz</a>"))
  (test "comments and processing instructions dropped" '(*TOP* (a "xy"))
        (xml-parse-string "<?xml version='1.0'?><?pi data?><a>x<!-- c -->y<?p q?></a><!-- end -->"))
  (test "Tiled's old DOCTYPE line is accepted and not fetched" '(*TOP* (map (@ (w "1"))))
        (xml-parse-string
         "<?xml version=\"1.0\"?>\n<!DOCTYPE map SYSTEM \"http://mapeditor.org/dtd/1.0/map.dtd\">\n<map w=\"1\"/>"))
  (test "internal entity declared in the document expands" '(*TOP* (a "hello, hello"))
        (xml-parse-string "<!DOCTYPE a [<!ENTITY h 'hello'>]><a>&h;, &h;</a>"))
  (test "UTF-8 text kept as UTF-8 bytes" '(*TOP* (a (@ (n "\xc3\xa9t\xc3\xa9")) "\xe2\x82\xac"))
        (xml-parse-string "<a n='\xc3\xa9t\xc3\xa9'>\xe2\x82\xac</a>"))
  (test "ISO-8859-1 document comes out as UTF-8" '(*TOP* (a "\xc3\xa9"))
        (xml-parse-string "<?xml version='1.0' encoding='ISO-8859-1'?><a>\xe9</a>"))
  (test "character reference beyond the BMP" '(*TOP* (a "\xf0\x9f\x98\x80"))
        (xml-parse-string "<a>&#x1F600;</a>"))
  (test "many siblings" 5000
        (length (sxml-children
                 (sxml-child (xml-parse-string
                              (string-append "<r>" (xml-repeat-string "<t a='1'/>" 5000) "</r>"))
                             'r)
                 't)))
  (test "deep nesting (20000 levels) without recursion trouble" 20000
        (let loop ((node (sxml-child (xml-parse-string
                                      (string-append (xml-repeat-string "<n>" 20000)
                                                     (xml-repeat-string "</n>" 20000)))
                                     'n))
                   (depth 1))
          (let ((child (sxml-child node 'n)))
            (if child (loop child (+ depth 1)) depth)))))

(test-group "xml: large input"
  ;; The string parser feeds 1 MiB chunks; text crossing a chunk boundary
  ;; must still come back as one string.
  (let* ((body (make-string (* 3 1024 1024) #\7))
         (tree (xml-parse-string (string-append "<d a='b'>" body "</d>"))))
    (test "3 MiB text node is one string" (* 3 1024 1024)
          (string-length (sxml-text (sxml-child tree 'd))))
    (test "3 MiB text node content" #t
          (string=? body (sxml-text (sxml-child tree 'd)))))
  (let* ((csv (string-intersperse (map number->string (xml-iota 200000)) ","))
         (tree (xml-parse-string (string-append "<data encoding='csv'>\n" csv "\n</data>"))))
    (test "200000-cell CSV text intact" (string-append "\n" csv "\n")
          (sxml-text (sxml-child tree 'data)))))

(test-group "xml: helpers"
  (let* ((tree (xml-parse-string xml-small-doc))
         (map-node (sxml-child tree 'map))
         (layer (sxml-child map-node 'layer)))
    (test "sxml-attr" "1.10" (sxml-attr map-node 'version))
    (test "sxml-attr by string name" "2" (sxml-attr map-node "width"))
    (test "sxml-attr missing -> #f" #f (sxml-attr map-node 'nope))
    (test "sxml-attr missing -> default" "dflt" (sxml-attr map-node 'nope "dflt"))
    (test "sxml-attr on element without attributes" 'none
          (sxml-attr '(x "text") 'a 'none))
    (test "sxml-attrs" '((id "1") (name "a")) (sxml-attrs layer))
    (test "sxml-children (all elements, no text, no @)" '(layer objectgroup)
          (map car (sxml-children map-node)))
    (test "sxml-children by tag" '((layer (@ (id "1") (name "a"))
                                          "\n  " (data (@ (encoding "csv")) "1,2\n3,4") "\n "))
          (sxml-children map-node 'layer))
    (test "sxml-children none" '() (sxml-children map-node 'tileset))
    (test "sxml-children of *TOP*" '(map) (map car (sxml-children tree)))
    (test "sxml-child first" "7"
          (sxml-attr (sxml-child (sxml-child map-node 'objectgroup) 'object) 'id))
    (test "sxml-child missing" #f (sxml-child map-node 'tileset))
    (test "sxml-child picks the first of several" "1"
          (sxml-attr (sxml-child (cadr (xml-parse-string "<r><p n='1'/><p n='2'/></r>")) 'p) 'n))
    (test "sxml-text" "1,2\n3,4" (sxml-text (sxml-child layer 'data)))
    (test "sxml-text concatenates direct text only" "ab"
          (sxml-text (cadr (xml-parse-string "<r>a<x>IGNORED</x>b</r>"))))
    (test "sxml-text with no text" "" (sxml-text (sxml-child map-node 'objectgroup)))))

(test-group "xml: errors name source, line, column and expat's reason"
  (test-error "mismatched tag" (xml-error-is "maps/level1.tmx:3:5: XML parse error: mismatched tag")
              (xml-parse-string "<map>\n <layer>\n  </map>" "maps/level1.tmx"))
  (test-error "default source name is \"string\""
              (xml-error-is "string:1:1: XML parse error: no element found")
              (xml-parse-string ""))
  (test-error "truncated document" (xml-error-mentions "no element found")
              (xml-parse-string "<a><b>text"))
  (test-error "unclosed attribute" (xml-error-mentions "t.xml:1:")
              (xml-parse-string "<a b='1>" "t.xml"))
  (test-error "junk after root" (xml-error-is "s:1:5: XML parse error: junk after document element")
              (xml-parse-string "<a/><b/>" "s"))
  (test-error "undefined entity" (xml-error-mentions "undefined entity")
              (xml-parse-string "<a>&nope;</a>"))
  (test-error "embedded NUL byte" (xml-error-mentions "x:1:5: XML parse error: not well-formed")
              (xml-parse-string (string-append "<a>x" (string (integer->char 0)) "y</a>") "x"))
  (test-error "invalid UTF-8 byte" (xml-error-mentions "not well-formed (invalid token)")
              (xml-parse-string "<a>\xff\xfe</a>"))
  (test-error "overlong UTF-8 sequence" (xml-error-mentions "not well-formed (invalid token)")
              (xml-parse-string "<a>\xc0\xaf</a>"))
  (test-error "truncated UTF-8 sequence at the end of text" (xml-error-mentions "XML parse error")
              (xml-parse-string "<a>\xe2\x82</a>"))
  (test-error "unknown encoding" (xml-error-mentions "unknown encoding")
              (xml-parse-string "<?xml version='1.0' encoding='X-NOPE'?><a/>"))
  (test "condition properties"
        '("src.tmx" 2 6 "mismatched tag")
        (condition-case (xml-parse-string "<a>\n<b></a>" "src.tmx")
          (e (xml-error)
             (map (lambda (p) ((condition-property-accessor 'xml-error p) e))
                  '(source line column reason)))))
  (test "it is an exn too" #t
        (condition-case (xml-parse-string "<a>")
          (e (exn) #t)))
  (test-error "not a string" (xml-parse-string 'oops)))

(test-group "xml: every truncation of a small document"
  (let* ((doc "<?xml version=\"1.0\"?><map a=\"1\"><l n='&amp;'>x<![CDATA[y]]>&#x41;</l><!--c--><e/></map>")
         (n (string-length doc))
         (outcomes (map (lambda (i) (xml-outcome (substring doc 0 i))) (xml-iota n))))
    (test "every proper prefix raises an xml-error" n
          (xml-count-errors outcomes))
    (test "the whole document parses" 'ok (xml-outcome doc))
    (test "the whole document plus trailing whitespace parses" 'ok
          (xml-outcome (string-append doc "\n  \n")))))

(test-group "xml: random corruption never crashes"
  (let* ((doc "<?xml version=\"1.0\"?><map a=\"1\"><l n='&amp;'>x<![CDATA[y]]>&#x41;\xc3\xa9</l><!--c--><e/></map>")
         (n (string-length doc)))
    (set-pseudo-random-seed! "downstroke-xml")
    (test "2000 mutated documents each parse or raise an xml-error" 2000
          (let loop ((k 0) (good 0))
            (if (= k 2000)
                good
                (let ((s (string-copy doc)))
                  (do ((j (+ 1 (pseudo-random-integer 3)) (- j 1))) ((zero? j))
                    (string-set! s (pseudo-random-integer n)
                                 (integer->char (pseudo-random-integer 256))))
                  (loop (+ k 1)
                        (if (memq (xml-outcome s) '(ok error)) (+ good 1) good))))))))

(test-group "xml: entities are not a way in"
  (test-error "billion laughs refused" (xml-error-mentions "amplification")
              (xml-parse-string
               (string-append
                "<?xml version=\"1.0\"?><!DOCTYPE lolz [<!ENTITY lol \"lol\">"
                "<!ENTITY lol1 \"&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;\">"
                "<!ENTITY lol2 \"&lol1;&lol1;&lol1;&lol1;&lol1;&lol1;&lol1;&lol1;&lol1;&lol1;\">"
                "<!ENTITY lol3 \"&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;\">"
                "<!ENTITY lol4 \"&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;&lol3;\">"
                "<!ENTITY lol5 \"&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;&lol4;\">"
                "<!ENTITY lol6 \"&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;&lol5;\">"
                "<!ENTITY lol7 \"&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;&lol6;\">"
                "<!ENTITY lol8 \"&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;&lol7;\">"
                "<!ENTITY lol9 \"&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;&lol8;\">"
                "]><lolz>&lol9;</lolz>")))
  (test-error "billion laughs in an attribute refused" (xml-error-mentions "amplification")
              (xml-parse-string
               (string-append
                "<!DOCTYPE l [<!ENTITY a \"aaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaa\">"
                "<!ENTITY b \"&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;\">"
                "<!ENTITY c \"&b;&b;&b;&b;&b;&b;&b;&b;&b;&b;&b;&b;&b;&b;&b;&b;\">"
                "<!ENTITY d \"&c;&c;&c;&c;&c;&c;&c;&c;&c;&c;&c;&c;&c;&c;&c;&c;\">"
                "<!ENTITY e \"&d;&d;&d;&d;&d;&d;&d;&d;&d;&d;&d;&d;&d;&d;&d;&d;\">"
                "<!ENTITY f \"&e;&e;&e;&e;&e;&e;&e;&e;&e;&e;&e;&e;&e;&e;&e;&e;\">"
                "]><l v=\"&f;\"/>")))
  (test-error "external general entity refused, not read"
              (xml-error-mentions "external entity refused (SYSTEM \"file:///etc/passwd\")")
              (xml-parse-string
               "<!DOCTYPE a [<!ENTITY e SYSTEM \"file:///etc/passwd\">]><a>&e;</a>"))
  (test-error "entity that only an external DTD could declare is refused"
              (xml-error-mentions "entity \"e\" is not declared in the document")
              (xml-parse-string "<!DOCTYPE a SYSTEM \"/etc/passwd\"><a>&e;</a>"))
  (test "external parameter entity in the internal subset is not read" '(*TOP* (a "ok"))
        (xml-parse-string
         "<!DOCTYPE a [<!ENTITY % p SYSTEM \"file:///etc/passwd\"> %p;]><a>ok</a>")))

(test-group "xml: files"
  (let ((path (create-temporary-file ".tmx")))
    (xml-write-file path xml-small-doc)
    (test "file parses to the same tree as the string"
          (xml-parse-string xml-small-doc) (xml-parse-file path))
    (xml-write-file path "<map>\n<layer>\n</map>\n")
    (test-error "parse error names the file path"
                (xml-error-is (string-append path ":3:3: XML parse error: mismatched tag"))
                (xml-parse-file path))
    (xml-write-file path "")
    (test-error "empty file" (xml-error-mentions (string-append path ":1:1: XML parse error: no element found"))
                (xml-parse-file path))
    ;; About 6 MiB: parsed in many chunks, text merged across them.
    (let* ((row (string-append (string-intersperse (map number->string (xml-iota 100)) ",") ",\n"))
           (rows 20000)
           (tiles (xml-repeat-string "<tile id='3'><properties><property name='p' value='v'/></properties></tile>\n" 20000)))
      (xml-write-file path (string-append "<map><tileset>" tiles "</tileset><layer><data encoding='csv'>"
                                          (xml-repeat-string row rows) "</data></layer></map>"))
      (let ((tree (xml-parse-file path)))
        (test "large file: all tiles" 20000
              (length (sxml-children (sxml-child (sxml-child tree 'map) 'tileset) 'tile)))
        (test "large file: CSV text length" (* rows (string-length row))
              (string-length (sxml-text (sxml-child (sxml-child (sxml-child tree 'map) 'layer) 'data))))))
    (delete-file path)
    (test-error "missing file names the path"
                (lambda (e) (and (xml-error? e)
                                 ((condition-predicate 'file) e)
                                 (string=? (error-text e)
                                           (string-append "xml-parse-file: cannot open \"" path
                                                          "\": No such file or directory"))))
                (xml-parse-file path)))
  (test-error "a directory is not a document" (xml-error-mentions "cannot read \"/tmp\"")
              (xml-parse-file "/tmp"))
  (test-error "path with a NUL byte" (xml-parse-file (string-append "a" (string (integer->char 0)) "b"))))
