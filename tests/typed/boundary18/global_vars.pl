tag ==> global_tag.
